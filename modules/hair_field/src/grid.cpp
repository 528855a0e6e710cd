#include "lapis/hair_field/grid.h"

#include <cmath>
#include <string>

#include "lapis/core/error.h"

namespace lapis::hair_field {

double estimate_multigrid_bytes(std::int64_t n) {
  const double nd = static_cast<double>(n);
  // Fine operator: 25 non-zeros/row, float value + int column (8 B). Galerkin coarse
  // levels: 125 non-zeros/row at 1/8 the rows per level, double master + float copy (20 B),
  // summing to ~ n * 125/7 * 20. Vectors: double field + 6 double CG vectors + 6 float
  // multigrid vectors, 3 columns each.
  const double fine = nd * 25 * 8;
  const double coarse = nd * 125.0 / 7.0 * 20.0;
  const double vectors = nd * 3 * (7 * 8 + 6 * 4 * 1.15);
  return fine + coarse + vectors;
}

double estimate_cholesky_bytes(std::int64_t n) {
  const double c = 38e6 / std::pow(50000.0, 4.0 / 3.0);
  return c * std::pow(static_cast<double>(n), 4.0 / 3.0) * 12.0;
}

Grid make_grid(const Eigen::AlignedBox3d& head_box, const GridOptions& options) {
  if (head_box.isEmpty() || !head_box.min().allFinite() || !head_box.max().allFinite() ||
      (head_box.max() - head_box.min()).minCoeff() <= 0)
    throw InvalidArgument("hair_field::make_grid(): head box is empty or not finite");
  if (!(options.target_unknowns >= 8) || !std::isfinite(options.target_unknowns))
    throw InvalidArgument("hair_field::make_grid(): target_unknowns must be >= 8, got " +
                          std::to_string(options.target_unknowns));
  const double est = estimate_multigrid_bytes(static_cast<std::int64_t>(options.target_unknowns));
  if (est > options.memory_limit_bytes)
    throw ResourceLimit("hair_field::make_grid(): a grid of " +
                        std::to_string(static_cast<long long>(options.target_unknowns)) + " unknowns needs about " +
                        std::to_string(est / (1 << 20)) + " MiB, more than the limit of " +
                        std::to_string(options.memory_limit_bytes / (1 << 20)) + " MiB");
  const Eigen::Vector3d ext = head_box.max() - head_box.min();
  Eigen::Vector3d lo = head_box.min(), hi = head_box.max();
  lo.x() -= options.margin_side * ext.x();
  hi.x() += options.margin_side * ext.x();
  lo.z() -= options.margin_side * ext.z();
  hi.z() += options.margin_side * ext.z();
  hi.y() += options.margin_top * ext.y();
  lo.y() -= options.margin_below * ext.y();
  const Eigen::Vector3d size = hi - lo;
  // (sx/d + 1)(sy/d + 1)(sz/d + 1) = target, solved for d by a few fixed-point steps.
  double d = std::cbrt(size.prod() / options.target_unknowns);
  for (int it = 0; it < 50; ++it) {
    const double cells = (size.array() / d + 1.0).prod();
    d *= std::cbrt(cells / options.target_unknowns);
  }
  Grid g;
  g.spacing = d;
  for (int a = 0; a < 3; ++a) g.dims[a] = std::max(2, static_cast<int>(std::lround(size[a] / d)) + 1);
  // Centre the node lattice on the enlarged box.
  const Eigen::Vector3d span(d * (g.dims[0] - 1), d * (g.dims[1] - 1), d * (g.dims[2] - 1));
  g.origin = 0.5 * (lo + hi) - 0.5 * span;
  return g;
}

}  // namespace lapis::hair_field
