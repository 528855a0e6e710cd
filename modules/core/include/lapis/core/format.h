// Numbers in messages. std::to_string(double) prints "%f": a range of [1e-3, 1e300] came out
// as "[0.001000, 1000000000000000052504760255204420248704468581108159…]". "%g" keeps six
// significant digits and switches to an exponent when that is shorter: "[0.001, 1e+300]".
#pragma once

#include <cstdio>
#include <string>

namespace lapis {

inline std::string format_number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

}  // namespace lapis
