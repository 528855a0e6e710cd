#include "lapis/geometry/connected_region.h"

#include <algorithm>
#include <string>

#include "lapis/core/error.h"

namespace lapis::geometry {

std::vector<int> connected_region(const Connectivity& conn, int seed, const std::vector<char>& allowed) {
  const int n = conn.num_vertices();
  if (seed < 0 || seed >= n)
    throw InvalidArgument("geometry::connected_region(): seed " + std::to_string(seed) + " out of range [0, " +
                          std::to_string(n) + ")");
  if (!allowed.empty() && static_cast<int>(allowed.size()) != n)
    throw InvalidArgument("geometry::connected_region(): allowed has " + std::to_string(allowed.size()) +
                          " entries, expected one per vertex (" + std::to_string(n) + ")");
  auto ok = [&](int v) { return allowed.empty() || allowed[static_cast<size_t>(v)] != 0; };
  if (!ok(seed)) return {};
  std::vector<char> seen(static_cast<size_t>(n), 0);
  std::vector<int> region{seed};
  seen[static_cast<size_t>(seed)] = 1;
  for (size_t head = 0; head < region.size(); ++head)
    for (int w : conn.vertex_neighbors(region[head]))
      if (!seen[static_cast<size_t>(w)] && ok(w)) seen[static_cast<size_t>(w)] = 1, region.push_back(w);
  std::sort(region.begin(), region.end());
  return region;
}

}  // namespace lapis::geometry
