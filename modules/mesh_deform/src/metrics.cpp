#include "lapis/mesh_deform/metrics.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Geometry>

#include "lapis/core/error.h"
#include "lapis/geometry/polar.h"
#include "rotation_fit.h"
#include "stencil.h"

namespace lapis::mesh_deform {

Summary summarize(std::vector<double> v) {
  Summary s;
  if (v.empty()) return s;
  s.count = static_cast<int>(v.size());
  double sum = 0;
  for (double x : v) sum += x;
  s.mean = sum / v.size();
  const size_t k = std::min(v.size() - 1, static_cast<size_t>(std::ceil(0.95 * v.size())) - 1);
  std::nth_element(v.begin(), v.begin() + static_cast<long>(k), v.end());
  s.p95 = v[k];
  s.max = *std::max_element(v.begin(), v.end());
  return s;
}

namespace {

double corner_angle(const Eigen::RowVector3d& o, const Eigen::RowVector3d& a, const Eigen::RowVector3d& b) {
  const Eigen::RowVector3d u = a - o, w = b - o;
  return std::atan2(u.cross(w).norm(), u.dot(w));
}

}  // namespace

Distortion distortion(const geometry::TriMesh& rest, const geometry::Vertices& X) {
  if (X.rows() != rest.V.rows())
    throw InvalidArgument("mesh_deform::distortion(): deformed positions have " + std::to_string(X.rows()) +
                          " rows, expected " + std::to_string(rest.V.rows()));
  const geometry::Vertices& V = rest.V;
  const detail::Stencil s = detail::make_stencil(V, rest.F, LaplacianWeights::Cotangent);
  Distortion d;

  std::vector<double> edges;
  for (int i = 0; i < s.size(); ++i)
    for (int k = s.offsets[i]; k < s.offsets[i + 1]; ++k) {
      const int j = s.nbr[k];
      if (j < i) continue;
      const double l0 = (V.row(i) - V.row(j)).norm();
      if (l0 > 0) edges.push_back(std::abs((X.row(i) - X.row(j)).norm() / l0 - 1));
    }
  d.edge_length = summarize(std::move(edges));

  const geometry::Vertices d0 = detail::laplacian_coordinates(s, V), d1 = detail::laplacian_coordinates(s, X);
  double mean = 0;
  for (int i = 0; i < d0.rows(); ++i) mean += d0.row(i).norm();
  mean /= std::max<Eigen::Index>(1, d0.rows());
  std::vector<double> lap;
  for (int i = 0; i < d0.rows(); ++i) {
    const double l0 = d0.row(i).norm();
    if (l0 > 1e-8 * mean) lap.push_back(std::abs(d1.row(i).norm() / l0 - 1));
  }
  d.laplacian_length = summarize(std::move(lap));

  std::vector<double> angles;
  for (int f = 0; f < rest.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int o = rest.F(f, c), a = rest.F(f, (c + 1) % 3), b = rest.F(f, (c + 2) % 3);
      angles.push_back(
          std::abs(corner_angle(X.row(o), X.row(a), X.row(b)) - corner_angle(V.row(o), V.row(a), V.row(b))));
    }
  d.angle = summarize(std::move(angles));

  // The energy ArapDeformer minimizes: cotangent weights with obtuse angles clamped to zero,
  // without which the sum has no lower bound (stencil.h, ObtuseAngles).
  const detail::Stencil sa =
      detail::make_stencil(V, rest.F, LaplacianWeights::Cotangent, detail::ObtuseAngles::ClampToZero);
  double energy = 0, norm = 0;
  for (int i = 0; i < sa.size(); ++i) {
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
    for (int k = sa.offsets[i]; k < sa.offsets[i + 1]; ++k) {
      const int j = sa.nbr[k];
      A += sa.w[k] * (X.row(i) - X.row(j)).transpose() * (V.row(i) - V.row(j));
    }
    const Eigen::Matrix3d R = geometry::polar_rotation(A);
    for (int k = sa.offsets[i]; k < sa.offsets[i + 1]; ++k) {
      const int j = sa.nbr[k];
      const Eigen::Vector3d e = (V.row(i) - V.row(j)).transpose(), et = (X.row(i) - X.row(j)).transpose();
      energy += sa.w[k] * (et - R * e).squaredNorm();
      norm += sa.w[k] * e.squaredNorm();
    }
  }
  d.arap_energy = norm > 0 ? energy / norm : 0;
  return d;
}

}  // namespace lapis::mesh_deform
