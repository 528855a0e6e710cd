#include "lapis/mesh_merge/refine.h"

#include <cmath>

#include "lapis/geometry/connectivity.h"

namespace lapis::mesh_merge {

int split_boundary_edges(geometry::TriMesh& mesh) {
  const geometry::Connectivity conn(mesh);
  std::vector<Eigen::RowVector3i> faces;
  std::vector<Eigen::RowVector3d> added;
  const int n = mesh.num_vertices();
  for (int f = 0; f < mesh.num_faces(); ++f) {
    int k = 0;
    while (k < 3 && !conn.is_boundary_edge(conn.face_edge(f, k))) ++k;
    if (k == 3) {
      faces.push_back(mesh.F.row(f));
      continue;
    }
    // Only the first boundary edge of a face is split: a face with two boundary edges (an ear)
    // keeps the other one, and the next level catches it.
    const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3), c = mesh.F(f, (k + 2) % 3);
    const int m = n + static_cast<int>(added.size());
    added.push_back(0.5 * (mesh.V.row(a) + mesh.V.row(b)));
    faces.emplace_back(a, m, c);
    faces.emplace_back(m, b, c);
  }
  mesh.V.conservativeResize(n + static_cast<Eigen::Index>(added.size()), 3);
  for (size_t i = 0; i < added.size(); ++i) mesh.V.row(n + static_cast<Eigen::Index>(i)) = added[i];
  mesh.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (size_t i = 0; i < faces.size(); ++i) mesh.F.row(static_cast<Eigen::Index>(i)) = faces[i];
  return static_cast<int>(added.size());
}

int refine_short_boundary(geometry::TriMesh& mesh, double min_ratio, int max_levels) {
  int levels = 0;
  while (levels < max_levels) {
    const geometry::Connectivity conn(mesh);
    size_t boundary = 0;
    for (const auto& loop : conn.boundary_loops()) boundary += loop.size();
    if (boundary == 0 || double(boundary) >= min_ratio * std::sqrt(double(mesh.num_vertices()))) break;
    split_boundary_edges(mesh);
    ++levels;
  }
  return levels;
}

}  // namespace lapis::mesh_merge
