#include "lapis/mesh_merge/metrics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "lapis/core/error.h"
#include "lapis/geometry/laplacian.h"
#include "lapis/geometry/normals.h"
#include "lapis/geometry/polar.h"

namespace lapis::mesh_merge {

namespace {

double deg(double rad) { return rad * 180.0 / std::numbers::pi; }

double angle_between(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

// Folded strip edges that join two target vertices along an edge the target had, folded there
// already: the strip face took the place of the target's face on that edge.
int inherited_folds(const TriMesh& target, const MergeResult& r) {
  std::vector<int> target_of(static_cast<size_t>(r.mesh.num_vertices()), -1);
  for (int v = 0; v < target.num_vertices(); ++v)
    if (r.target_map[v] >= 0) target_of[r.target_map[v]] = v;
  const Connectivity conn(r.mesh), own(target);
  const Vertices N = geometry::face_normals(r.mesh), own_normals = geometry::face_normals(target);
  const auto folded = [](const Vertices& normals, std::array<int, 2> faces) {
    return deg(angle_between(normals.row(faces[0]).transpose(), normals.row(faces[1]).transpose())) >
           geometry::kFoldedDihedralDeg;
  };
  std::vector<char> counted(static_cast<size_t>(conn.num_edges()), 0);
  int count = 0;
  for (int f : r.strip_faces)
    for (int k = 0; k < 3; ++k) {
      const int e = conn.face_edge(f, k);
      const auto [a, b] = conn.edges()[e];
      if (counted[e] || conn.edge_face_count(e) != 2 || target_of[a] < 0 || target_of[b] < 0) continue;
      counted[e] = 1;
      const int was = own.find_edge(target_of[a], target_of[b]);
      count += was >= 0 && own.edge_face_count(was) == 2 && folded(N, conn.edge_faces(e)) &&
               folded(own_normals, own.edge_faces(was));
    }
  return count;
}

}  // namespace

double bbox_diagonal(const Vertices& V) {
  if (V.rows() == 0) return 0;
  return (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
}

std::vector<double> dihedral_deviation_deg(const TriMesh& mesh, const std::vector<int>& faces) {
  const Connectivity conn(mesh);
  const Vertices N = geometry::face_normals(mesh);
  std::vector<char> want(static_cast<size_t>(conn.num_edges()), faces.empty() ? 1 : 0);
  for (int f : faces)
    for (int k = 0; k < 3; ++k) want[conn.face_edge(f, k)] = 1;
  std::vector<double> out;
  for (int e = 0; e < conn.num_edges(); ++e) {
    if (!want[e] || conn.edge_face_count(e) != 2) continue;
    const auto [f, g] = conn.edge_faces(e);
    out.push_back(deg(angle_between(N.row(f).transpose(), N.row(g).transpose())));
  }
  return out;
}

SeamQuality seam_quality(const TriMesh& target, const MergeResult& r) {
  SeamQuality q;
  const Connectivity conn(r.mesh);
  std::vector<char> on_seam(static_cast<size_t>(r.mesh.num_vertices()), 0);
  for (int v : r.seam_vertices) on_seam[v] = 1;
  for (int e = 0; e < conn.num_edges(); ++e) {
    const auto [a, b] = conn.edges()[e];
    if (conn.is_boundary_edge(e) && on_seam[a] && on_seam[b]) ++q.seam_boundary_edges;
  }
  geometry::ValidationOptions vo;
  vo.check_duplicates = false;
  vo.check_orientation = false;
  const geometry::ValidationReport rep = geometry::validate(r.mesh, vo);
  q.non_manifold_edges = static_cast<int>(rep.non_manifold_edges.size());
  q.non_manifold_vertices = static_cast<int>(rep.non_manifold_vertices.size());
  q.degenerate_faces = static_cast<int>(rep.degenerate_faces.size());

  double min_angle = 180;
  for (int f : r.strip_faces)
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d p = r.mesh.V.row(r.mesh.F(f, k));
      const Eigen::Vector3d a = r.mesh.V.row(r.mesh.F(f, (k + 1) % 3)).transpose() - p;
      const Eigen::Vector3d b = r.mesh.V.row(r.mesh.F(f, (k + 2) % 3)).transpose() - p;
      min_angle = std::min(min_angle, deg(angle_between(a, b)));
    }
  q.min_strip_angle_deg = r.strip_faces.empty() ? 0 : min_angle;

  std::vector<char> smoothed(static_cast<size_t>(r.mesh.num_vertices()), 0);
  for (int v : r.smoothed) smoothed[v] = 1;
  for (int v : r.transition_vertices) smoothed[v] = 1;  // a kept target band deforms by design (§3.3.3)
  double moved = 0;
  for (int v = 0; v < target.num_vertices(); ++v) {
    const int m = r.target_map[v];
    if (m >= 0 && !smoothed[m]) moved = std::max(moved, (r.mesh.V.row(m) - target.V.row(v)).norm());
  }
  q.max_target_displacement = moved / std::max(bbox_diagonal(target.V), 1e-300);

  const std::vector<double> seam = dihedral_deviation_deg(r.mesh, r.strip_faces);
  if (!seam.empty()) {
    double sum = 0;
    for (double a : seam) sum += a;
    q.seam_dihedral_mean_deg = sum / double(seam.size());
    q.seam_dihedral_max_deg = *std::max_element(seam.begin(), seam.end());
    q.inherited_folds = inherited_folds(target, r);
    q.folded_seam_edges = static_cast<int>(std::count_if(seam.begin(), seam.end(),
                                                         [](double a) { return a > geometry::kFoldedDihedralDeg; })) -
                          q.inherited_folds;
  }
  std::vector<double> own = dihedral_deviation_deg(target);
  if (!own.empty()) {
    double sum = 0;
    for (double a : own) sum += a;
    q.target_dihedral_mean_deg = sum / double(own.size());
    const size_t k = std::min(own.size() - 1, static_cast<size_t>(0.95 * double(own.size())));
    std::nth_element(own.begin(), own.begin() + static_cast<std::ptrdiff_t>(k), own.end());
    q.target_dihedral_p95_deg = own[k];
  }
  return q;
}

DetailPreservation detail_preservation(const TriMesh& source, const MergeResult& r) {
  DetailPreservation d;
  const int n = source.num_vertices();
  const Connectivity conn(source);
  Vertices merged = source.V;
  for (int v = 0; v < n; ++v)
    if (r.source_map[v] >= 0) merged.row(v) = r.mesh.V.row(r.source_map[v]);
  // Interior vertices still in the merged mesh with their whole 1-ring (a transition merge that
  // keeps the target's band removes the source's).
  auto kept = [&](int v) {
    if (r.source_map[v] < 0) return false;
    for (int u : conn.vertex_neighbors(v))
      if (r.source_map[u] < 0) return false;
    return true;
  };
  std::vector<int> interior;
  for (int v = 0; v < n; ++v)
    if (!conn.is_boundary_vertex(v) && !conn.is_isolated_vertex(v) && kept(v)) interior.push_back(v);
  if (interior.empty()) return d;

  const Eigen::SparseMatrix<double> L = geometry::cotan_laplacian(source);
  const Eigen::MatrixX3d delta = L * source.V, now = L * merged;
  double num = 0, den = 0;
  for (int v : interior) {
    const auto nb = conn.vertex_neighbors(v);
    Eigen::MatrixX3d from(nb.size() + 1, 3), to(nb.size() + 1, 3);
    from.row(0) = source.V.row(v);
    to.row(0) = merged.row(v);
    for (size_t k = 0; k < nb.size(); ++k) {
      from.row(static_cast<Eigen::Index>(k + 1)) = source.V.row(nb[k]);
      to.row(static_cast<Eigen::Index>(k + 1)) = merged.row(nb[k]);
    }
    const geometry::Similarity3 s = geometry::fit_similarity(from, to);
    const Eigen::Vector3d Td = s.linear() * delta.row(v).transpose();
    num += (now.row(v).transpose() - Td).squaredNorm();
    den += Td.squaredNorm();
  }
  d.laplacian_residual = den > 0 ? std::sqrt(num / den) : 0;

  Eigen::MatrixX3d from(interior.size(), 3), to(interior.size(), 3);
  for (size_t k = 0; k < interior.size(); ++k) {
    from.row(static_cast<Eigen::Index>(k)) = source.V.row(interior[k]);
    to.row(static_cast<Eigen::Index>(k)) = merged.row(interior[k]);
  }
  const geometry::Similarity3 s = geometry::fit_similarity(from, to);
  d.turn_deg = std::acos(std::clamp((s.R.trace() - 1) / 2, -1.0, 1.0)) * 180 / std::numbers::pi;
  const double diag = std::max(bbox_diagonal(merged), 1e-300);
  double sum = 0;
  for (Eigen::Index k = 0; k < from.rows(); ++k) {
    const double e = (s(from.row(k).transpose()) - to.row(k).transpose()).norm();
    d.max_distance = std::max(d.max_distance, e);
    sum += e;
  }
  d.mean_distance = sum / double(from.rows()) / diag;
  d.max_distance /= diag;
  return d;
}

double feature_distortion(const TriMesh& source, const MergeResult& r, const std::vector<int>& vertices) {
  const char* fn = "mesh_merge::feature_distortion(): ";
  if (vertices.size() < 3) throw InvalidArgument(std::string(fn) + "a part needs at least 3 vertices");
  Eigen::MatrixX3d from(static_cast<Eigen::Index>(vertices.size()), 3), to(from.rows(), 3);
  for (Eigen::Index i = 0; i < from.rows(); ++i) {
    const int v = vertices[static_cast<size_t>(i)];
    if (v < 0 || v >= source.num_vertices() || static_cast<size_t>(v) >= r.source_map.size() || r.source_map[v] < 0)
      throw InvalidArgument(std::string(fn) + "vertex " + std::to_string(v) + " is not a merged source vertex");
    from.row(i) = source.V.row(v), to.row(i) = r.mesh.V.row(r.source_map[v]);
  }
  const geometry::Similarity3 s = geometry::fit_similarity(from, to);
  double worst = 0;
  for (Eigen::Index i = 0; i < from.rows(); ++i)
    worst = std::max(worst, (s(from.row(i).transpose()) - to.row(i).transpose()).norm());
  return worst / std::max(bbox_diagonal(to), 1e-300);
}

}  // namespace lapis::mesh_merge
