#include "lapis/hair_sketch/field_detail.h"

#include <cmath>
#include <numbers>

#include "lapis/core/error.h"

namespace lapis::hair_sketch {

hair_field::Field wavy_example_field(const hair_field::Grid& grid, const Eigen::Vector3d& center,
                                     const FieldDetailOptions& options) {
  const std::string fn = "hair_sketch::wavy_example_field(): ";
  if (!(std::isfinite(options.amplitude) && options.amplitude >= 0))
    throw InvalidArgument(fn + "the field detail amplitude must be finite and not negative");
  if (!(std::isfinite(options.wavelength) && options.wavelength > 0))
    throw InvalidArgument(fn + "the field detail wavelength must be positive and finite");
  const auto n = static_cast<Eigen::Index>(grid.num_nodes());
  hair_field::Field t(n, 3);
  const double k = 2 * std::numbers::pi / options.wavelength;
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector3d p = grid.position(static_cast<int>(i));
    const Eigen::Vector2d radial(p.x() - center.x(), p.z() - center.z());
    const double r = radial.norm();
    // On the axis itself e_φ is undefined; its nodes lie inside the head and neck.
    const Eigen::Vector3d around =
        r > 1e-12 ? Eigen::Vector3d(-radial.y() / r, 0, radial.x() / r) : Eigen::Vector3d::Zero();
    t.row(i) = (options.amplitude * std::sin(k * p.y()) * around).transpose();
  }
  return t;
}

}  // namespace lapis::hair_sketch
