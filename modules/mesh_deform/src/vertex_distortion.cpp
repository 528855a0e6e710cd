#include "lapis/mesh_deform/vertex_distortion.h"

#include <cmath>
#include <string>

#include <Eigen/Geometry>

#include "lapis/core/error.h"
#include "stencil.h"

namespace lapis::mesh_deform {
namespace {

double corner_angle(const Eigen::RowVector3d& o, const Eigen::RowVector3d& a, const Eigen::RowVector3d& b) {
  const Eigen::RowVector3d u = a - o, w = b - o;
  return std::atan2(u.cross(w).norm(), u.dot(w));
}

}  // namespace

const char* to_string(DistortionField f) {
  switch (f) {
    case DistortionField::EdgeLength:
      return "edge length";
    case DistortionField::Angle:
      return "angle";
    case DistortionField::LaplacianLength:
      return "Laplacian magnitude";
  }
  return "?";
}

Eigen::VectorXd vertex_distortion(const geometry::TriMesh& rest, const geometry::Vertices& X, DistortionField field) {
  const geometry::Vertices& V = rest.V;
  const Eigen::Index n = V.rows();
  if (X.rows() != n)
    throw InvalidArgument("mesh_deform::vertex_distortion(): deformed positions have " + std::to_string(X.rows()) +
                          " rows, expected " + std::to_string(n));
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(n), count = Eigen::VectorXd::Zero(n);
  if (field == DistortionField::LaplacianLength) {
    const detail::Stencil s = detail::make_stencil(V, rest.F, LaplacianWeights::Cotangent);
    const geometry::Vertices d0 = detail::laplacian_coordinates(s, V), d1 = detail::laplacian_coordinates(s, X);
    const double mean = d0.rowwise().norm().mean();
    Eigen::VectorXd out = Eigen::VectorXd::Zero(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      const double l0 = d0.row(i).norm();
      if (l0 > 1e-8 * mean) out(i) = std::abs(d1.row(i).norm() / l0 - 1);
    }
    return out;
  }
  // Per face corner: the corner's angle change, or the change of the edge leaving it; each
  // interior edge is seen from both its faces and both its ends, so the weighting is even.
  for (Eigen::Index f = 0; f < rest.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int o = rest.F(f, c), a = rest.F(f, (c + 1) % 3), b = rest.F(f, (c + 2) % 3);
      double value = 0;
      if (field == DistortionField::Angle) {
        value = std::abs(corner_angle(X.row(o), X.row(a), X.row(b)) - corner_angle(V.row(o), V.row(a), V.row(b)));
      } else {
        const double l0 = (V.row(o) - V.row(a)).norm();
        if (!(l0 > 0)) continue;
        value = std::abs((X.row(o) - X.row(a)).norm() / l0 - 1);
        sum(a) += value, count(a) += 1;  // the edge belongs to both ends
      }
      sum(o) += value, count(o) += 1;
    }
  return (count.array() > 0).select(sum.array() / count.array().max(1.0), 0.0).matrix();
}

}  // namespace lapis::mesh_deform
