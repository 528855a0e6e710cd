#include "lapis/core/main_guard.h"

#include <cstdio>
#include <exception>

#include "lapis/core/error.h"

namespace lapis::core {

int guarded_main(const std::string& program, const std::function<int()>& body, const std::string& usage) {
  const char* name = program.c_str();
  try {
    return body();
  } catch (const UsageError& e) {
    if (usage.empty())
      std::fprintf(stderr, "%s: %s (see --help)\n", name, e.what());
    else
      std::fprintf(stderr, "%s: %s\n%s", name, e.what(), usage.c_str());
    return 2;
  } catch (const Error& e) {
    std::fprintf(stderr, "%s: error: %s\n", name, e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: internal error: %s\n", name, e.what());
    return 1;
  }
}

}  // namespace lapis::core
