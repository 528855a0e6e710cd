#include "lapis/hair_sketch/stream_curve.h"

#include "curve_sampling.h"

namespace lapis::hair_sketch {
using hair_field::Constraint;
using hair_field::Grid;

std::vector<Constraint> StreamCurve::constraints(const Grid& grid) const {
  const auto p = detail::resample(points, grid.spacing, "hair_sketch::StreamCurve::constraints()");
  std::vector<Constraint> out;
  for (size_t i = 0; i + 1 < p.size(); ++i) {
    const Eigen::Vector3d d = p[i + 1] - p[i];
    if (d.norm() <= 0) continue;
    detail::constrain_cell(grid, 0.5 * (p[i] + p[i + 1]), d.normalized(), out);
  }
  // Tail: continue the last direction; magnitudes 1 − k/(T+1) for the k-th extra segment.
  const Eigen::Vector3d last = (p.back() - p[p.size() - 2]).normalized();
  for (int k = 1; k <= tail_segments; ++k) {
    const double mag = 1.0 - static_cast<double>(k) / (tail_segments + 1);
    const Eigen::Vector3d mid = p.back() + (k - 0.5) * grid.spacing * last;
    detail::constrain_cell(grid, mid, mag * last, out);
  }
  return out;
}

}  // namespace lapis::hair_sketch
