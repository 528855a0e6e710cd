#include "cut_open.h"

#include <algorithm>
#include <numeric>

namespace lapis::mesh_merge::detail {
namespace {

int find_root(std::vector<int>& parent, int a) {
  while (parent[a] != a) a = parent[a] = parent[parent[a]];
  return a;
}

// Which faces around cut vertex c lie on the side that gets the twin. The cut edges split c's fan
// into two groups (faces joined across non-cut edges); the group holding a face that runs along
// the cut in its winding order (directed edge prev -> c or c -> next) lies on the path's left.
// Empty when the fan does not split into exactly two groups.
std::vector<char> upper_side(const geometry::Connectivity& conn, const geometry::Faces& F, const std::vector<int>& cut,
                             size_t k, bool reversed) {
  const int c = cut[k];
  const int prev = k > 0 ? cut[k - 1] : -1, next = k + 1 < cut.size() ? cut[k + 1] : -1;
  const auto fan = conn.vertex_faces(c);
  std::vector<int> parent(fan.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto slot = [&](int f) { return static_cast<int>(std::find(fan.begin(), fan.end(), f) - fan.begin()); };
  for (int w : conn.vertex_neighbors(c)) {
    if (w == prev || w == next) continue;
    const auto ef = conn.edge_faces(conn.find_edge(c, w));
    if (ef[0] >= 0 && ef[1] >= 0) parent[find_root(parent, slot(ef[0]))] = find_root(parent, slot(ef[1]));
  }
  int left = -1, groups = 0;
  for (size_t i = 0; i < fan.size(); ++i) {
    if (find_root(parent, static_cast<int>(i)) == static_cast<int>(i)) ++groups;
    for (int j = 0; j < 3; ++j) {
      const int a = F(fan[i], j), b = F(fan[i], (j + 1) % 3);
      if ((a == prev && b == c) || (a == c && b == next)) left = find_root(parent, static_cast<int>(i));
    }
  }
  if (groups != 2 || left < 0) return {};
  std::vector<char> upper(fan.size());
  for (size_t i = 0; i < fan.size(); ++i) upper[i] = (find_root(parent, static_cast<int>(i)) == left) != reversed;
  return upper;
}

}  // namespace

CutOpen cut_open(const geometry::Connectivity& conn, const geometry::Faces& F, const std::vector<int>& cut,
                 bool reversed) {
  CutOpen out;
  out.faces = F;
  for (size_t k = 0; k < cut.size(); ++k) {
    const std::vector<char> upper = upper_side(conn, F, cut, k, reversed);
    if (upper.empty()) {
      out.failed_at = cut[k];
      out.faces.resize(0, 3);
      return out;
    }
    const auto fan = conn.vertex_faces(cut[k]);
    for (size_t i = 0; i < fan.size(); ++i)
      if (upper[i])
        for (int j = 0; j < 3; ++j)
          if (F(fan[i], j) == cut[k]) out.faces(fan[i], j) = conn.num_vertices() + static_cast<int>(k);
  }
  return out;
}

}  // namespace lapis::mesh_merge::detail
