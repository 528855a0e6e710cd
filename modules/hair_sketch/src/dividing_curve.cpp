#include "lapis/hair_sketch/dividing_curve.h"

#include <cmath>

#include "curve_sampling.h"

namespace lapis::hair_sketch {
using hair_field::Constraint;
using hair_field::Grid;

namespace {

struct Frame {
  Eigen::Vector3d x, y, z;
};

// Local frame at p with curve tangent t and tilt alpha (§4.5).
Frame local_frame(const Head& head, const Eigen::Vector3d& p, const Eigen::Vector3d& t, double alpha) {
  Frame f;
  f.y = head.closest(p).first;
  Eigen::Vector3d z = (t - t.dot(f.y) * f.y);
  if (z.norm() < 1e-12) {
    Eigen::Vector3d u, v;
    detail::orthonormal_frame(f.y, u, v);
    z = u;
  }
  z.normalize();
  f.z = Eigen::AngleAxisd(alpha, f.y) * z;
  f.x = f.y.cross(f.z).normalized();
  return f;
}

Eigen::Vector3d tangent_at(const std::vector<Eigen::Vector3d>& p, size_t i) {
  const size_t a = i == 0 ? 0 : i - 1, b = std::min(i + 1, p.size() - 1);
  return (p[b] - p[a]).normalized();
}

}  // namespace

std::vector<Constraint> DividingCurve::constraints(const Grid& grid, const Head& head) const {
  const auto p = detail::resample(points, grid.spacing, "hair_sketch::DividingCurve::constraints()");
  const double d = grid.spacing;
  std::vector<Constraint> out;
  // Gaussian g(u) = h (exp(−(u−σ)²/2σ²) − e^{−1/2}): its inflexion point u = 0 is p, it
  // rises to a crest at u = σ and falls beyond: hair lifts off the parting, then drops.
  const double e = std::exp(-0.5);
  auto slope = [&](double u) {
    return -height * (u - sigma) / (sigma * sigma) * std::exp(-(u - sigma) * (u - sigma) / (2 * sigma * sigma));
  };
  auto value = [&](double u) { return height * (std::exp(-(u - sigma) * (u - sigma) / (2 * sigma * sigma)) - e); };
  for (size_t i = 0; i < p.size(); ++i) {
    const double s = p.size() > 1 ? static_cast<double>(i) / (p.size() - 1) : 0.0;
    const Frame f = local_frame(head, p[i], tangent_at(p, i), alpha0 + s * (alpha1 - alpha0));
    for (int side = -1; side <= 1; side += 2) {
      for (int k = 1; k <= samples_per_side; ++k) {
        const double u = k;
        const Eigen::Vector3d q = p[i] + d * (side * u * f.x + value(u) * f.y);
        const Eigen::Vector3d dir = (side * f.x + slope(u) * f.y).normalized();
        detail::constrain_nearest(grid, q, dir, out);
      }
      // Discontinuity vector half a spacing off the parting, pointing away from it.
      detail::constrain_nearest(grid, p[i] + 0.5 * d * side * f.x, discontinuity * side * f.x, out);
    }
  }
  return out;
}

Eigen::Vector3d dividing_side_axis(const DividingCurve& curve, const Head& head, double s) {
  double length = 0;
  for (size_t i = 1; i < curve.points.size(); ++i) length += (curve.points[i] - curve.points[i - 1]).norm();
  const auto p = detail::resample(curve.points, length / 64, "hair_sketch::dividing_side_axis()");
  const size_t i = std::min(p.size() - 1, static_cast<size_t>(std::lround(s * (p.size() - 1))));
  return local_frame(head, p[i], tangent_at(p, i), curve.alpha0 + s * (curve.alpha1 - curve.alpha0)).x;
}

}  // namespace lapis::hair_sketch
