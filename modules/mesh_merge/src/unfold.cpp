#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "lapis/geometry/mesh_edit.h"
#include "lapis/mesh_merge/zip.h"

namespace lapis::mesh_merge {

namespace {

Eigen::Vector3d face_normal(const TriMesh& m, int f) {
  const Eigen::Vector3d a = m.V.row(m.F(f, 0)).transpose(), b = m.V.row(m.F(f, 1)).transpose(),
                        c = m.V.row(m.F(f, 2)).transpose();
  return (b - a).cross(c - a).normalized();
}

}  // namespace

int unfold_seam(TriMesh& mesh, const std::vector<int>& strip_faces, const std::vector<int>& movable, int max_rounds,
                double lambda) {
  const Connectivity conn(mesh);
  std::vector<char> can_move(static_cast<size_t>(mesh.num_vertices()), 0);
  for (int v : movable) can_move[v] = 1;
  std::vector<int> edges;
  for (int f : strip_faces)
    for (int k = 0; k < 3; ++k)
      if (conn.edge_face_count(conn.face_edge(f, k)) == 2) edges.push_back(conn.face_edge(f, k));
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  const double cos_fold = std::cos(geometry::kFoldedDihedralDeg * std::numbers::pi / 180);
  auto folded_edges = [&] {
    std::vector<int> out;
    for (int e : edges) {
      const auto [f, g] = conn.edge_faces(e);
      if (!(face_normal(mesh, f).dot(face_normal(mesh, g)) >= cos_fold)) out.push_back(e);
    }
    return out;
  };
  std::vector<int> folded = folded_edges();
  for (int round = 0; round < max_rounds && !folded.empty(); ++round) {
    std::vector<int> verts;
    for (int e : folded)
      for (int f : conn.edge_faces(e))
        for (int k = 0; k < 3; ++k)
          if (can_move[mesh.F(f, k)]) verts.push_back(mesh.F(f, k));
    std::sort(verts.begin(), verts.end());
    verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
    if (verts.empty()) break;
    Vertices next(static_cast<Eigen::Index>(verts.size()), 3);
    for (size_t k = 0; k < verts.size(); ++k) {
      Eigen::RowVector3d mean = Eigen::RowVector3d::Zero();
      const auto nb = conn.vertex_neighbors(verts[k]);
      for (int u : nb) mean += mesh.V.row(u);
      next.row(static_cast<Eigen::Index>(k)) =
          mesh.V.row(verts[k]) + lambda * (mean / double(nb.size()) - mesh.V.row(verts[k]));
    }
    for (size_t k = 0; k < verts.size(); ++k) mesh.V.row(verts[k]) = next.row(static_cast<Eigen::Index>(k));
    folded = folded_edges();
  }
  return static_cast<int>(folded.size());
}

}  // namespace lapis::mesh_merge
