#include "lapis/geometry/region_border.h"

#include <algorithm>
#include <string>

#include "lapis/core/error.h"

namespace lapis::geometry {

std::vector<int> near_region_border(const Connectivity& conn, const std::vector<char>& inside,
                                    const std::vector<int>& candidates, int rings) {
  const int n = conn.num_vertices();
  const char* fn = "geometry::near_region_border(): ";
  if (rings < 1) throw InvalidArgument(std::string(fn) + "rings = " + std::to_string(rings) + ", expected rings >= 1");
  if (static_cast<int>(inside.size()) != n)
    throw InvalidArgument(std::string(fn) + "inside has " + std::to_string(inside.size()) +
                          " entries, expected one per vertex (" + std::to_string(n) + ")");
  for (int v : candidates)
    if (v < 0 || v >= n)
      throw InvalidArgument(std::string(fn) + "candidate " + std::to_string(v) + " out of range [0, " +
                            std::to_string(n) + ")");
  // Breadth-first from the candidates, `rings` deep: a candidate is near when its search meets
  // a vertex outside. Candidates are few (a handle), the band they search small.
  std::vector<int> out, hops(static_cast<size_t>(n), -1), reached;
  for (int c : candidates) {
    bool near = !inside[static_cast<size_t>(c)];
    reached.assign(1, c);
    hops[static_cast<size_t>(c)] = 0;
    for (size_t head = 0; head < reached.size() && !near; ++head) {
      const int v = reached[head];
      if (hops[static_cast<size_t>(v)] == rings) continue;
      for (int w : conn.vertex_neighbors(v)) {
        if (hops[static_cast<size_t>(w)] >= 0) continue;
        if (!inside[static_cast<size_t>(w)]) {
          near = true;
          break;
        }
        hops[static_cast<size_t>(w)] = hops[static_cast<size_t>(v)] + 1;
        reached.push_back(w);
      }
    }
    for (int v : reached) hops[static_cast<size_t>(v)] = -1;
    if (near) out.push_back(c);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace lapis::geometry
