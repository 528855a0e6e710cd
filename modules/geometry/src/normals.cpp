#include "lapis/geometry/normals.h"

#include <Eigen/Geometry>

namespace lapis::geometry {
namespace {
// Twice the area times the unit normal of face f.
Eigen::RowVector3d area_normal(const TriMesh& m, Eigen::Index f) {
  const Eigen::RowVector3d a = m.V.row(m.F(f, 0)), b = m.V.row(m.F(f, 1)), c = m.V.row(m.F(f, 2));
  return (b - a).cross(c - a);
}
}  // namespace

Vertices face_normals(const TriMesh& mesh) {
  require_indices_in_range(mesh, "geometry::face_normals()");
  Vertices N(mesh.num_faces(), 3);
#pragma omp parallel for schedule(static)
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const Eigen::RowVector3d n = area_normal(mesh, f);
    const double len = n.norm();
    N.row(f) = len > 0 ? Eigen::RowVector3d(n / len) : Eigen::RowVector3d::Zero();
  }
  return N;
}

Eigen::VectorXd face_areas(const TriMesh& mesh) {
  require_indices_in_range(mesh, "geometry::face_areas()");
  Eigen::VectorXd A(mesh.num_faces());
#pragma omp parallel for schedule(static)
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) A[f] = 0.5 * area_normal(mesh, f).norm();
  return A;
}

Vertices vertex_normals(const TriMesh& mesh) {
  require_indices_in_range(mesh, "geometry::vertex_normals()");
  Vertices N = Vertices::Zero(mesh.num_vertices(), 3);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const Eigen::RowVector3d n = area_normal(mesh, f);
    for (int k = 0; k < 3; ++k) N.row(mesh.F(f, k)) += n;
  }
#pragma omp parallel for schedule(static)
  for (Eigen::Index v = 0; v < N.rows(); ++v) {
    const double len = N.row(v).norm();
    if (len > 0) N.row(v) /= len;
  }
  return N;
}

}  // namespace lapis::geometry
