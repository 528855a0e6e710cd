// Midpoint edge splits with the faces around them re-triangulated (mesh_edit.h).
#include <array>
#include <cstdint>
#include <string>
#include <unordered_map>

#include "lapis/core/error.h"
#include "lapis/geometry/mesh_edit.h"

namespace lapis::geometry {
namespace {

std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

// Appends the triangles of face (v0, v1, v2) whose edge k (from v[k] to v[k+1]) has midpoint
// m[k] (-1: not split), in the face's winding.
void split_face(const std::array<int, 3>& v, const std::array<int, 3>& m, std::vector<Eigen::RowVector3i>& out) {
  const int splits = (m[0] >= 0) + (m[1] >= 0) + (m[2] >= 0);
  if (splits == 0) {
    out.emplace_back(v[0], v[1], v[2]);
    return;
  }
  if (splits == 3) {
    out.emplace_back(v[0], m[0], m[2]);
    out.emplace_back(m[0], v[1], m[1]);
    out.emplace_back(m[2], m[1], v[2]);
    out.emplace_back(m[0], m[1], m[2]);
    return;
  }
  for (int k = 0; k < 3; ++k) {
    const int a = v[k], b = v[(k + 1) % 3], c = v[(k + 2) % 3];
    if (splits == 1 && m[k] >= 0) {
      out.emplace_back(a, m[k], c);
      out.emplace_back(m[k], b, c);
      return;
    }
    if (splits == 2 && m[k] < 0) {  // b–c and c–a split
      const int bc = m[(k + 1) % 3], ca = m[(k + 2) % 3];
      out.emplace_back(a, b, bc);
      out.emplace_back(a, bc, ca);
      out.emplace_back(bc, c, ca);
      return;
    }
  }
}

}  // namespace

int split_edges(TriMesh& mesh, const std::vector<std::pair<int, int>>& edges) {
  const int n = mesh.num_vertices();
  std::unordered_map<std::uint64_t, int> midpoint;
  std::vector<std::pair<int, int>> added;
  for (const auto& [a, b] : edges) {
    if (a < 0 || b < 0 || a >= n || b >= n || a == b)
      throw InvalidArgument("geometry::split_edges(): (" + std::to_string(a) + ", " + std::to_string(b) +
                            ") is not an edge between two of the mesh's " + std::to_string(n) + " vertices");
    if (midpoint.emplace(edge_key(a, b), n + static_cast<int>(added.size())).second) added.emplace_back(a, b);
  }
  std::vector<Eigen::RowVector3i> faces;
  faces.reserve(static_cast<size_t>(mesh.num_faces()) + 3 * added.size());
  std::vector<char> used(added.size(), 0);
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const std::array<int, 3> v{mesh.F(f, 0), mesh.F(f, 1), mesh.F(f, 2)};
    std::array<int, 3> m{-1, -1, -1};
    for (int k = 0; k < 3; ++k) {
      const auto it = midpoint.find(edge_key(v[k], v[(k + 1) % 3]));
      if (it != midpoint.end()) m[k] = it->second, used[static_cast<size_t>(it->second - n)] = 1;
    }
    split_face(v, m, faces);
  }
  for (size_t i = 0; i < added.size(); ++i)
    if (!used[i])
      throw InvalidArgument("geometry::split_edges(): (" + std::to_string(added[i].first) + ", " +
                            std::to_string(added[i].second) + ") is not an edge of the mesh");
  mesh.V.conservativeResize(n + static_cast<Eigen::Index>(added.size()), 3);
  for (size_t i = 0; i < added.size(); ++i)
    mesh.V.row(n + static_cast<Eigen::Index>(i)) = 0.5 * (mesh.V.row(added[i].first) + mesh.V.row(added[i].second));
  mesh.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (size_t i = 0; i < faces.size(); ++i) mesh.F.row(static_cast<Eigen::Index>(i)) = faces[i];
  return static_cast<int>(added.size());
}

}  // namespace lapis::geometry
