#include "handle_rotation_blend.h"

#include <cmath>

#include "lapis/geometry/polar.h"

namespace lapis::mesh_deform::detail {

std::vector<Eigen::Vector3d> region_rotation_vectors(const HandleTransforms& transforms) {
  std::vector<Eigen::Vector3d> r;
  r.reserve(transforms.regions.size());
  for (const Eigen::Matrix4d& T : transforms.regions) {
    const Eigen::AngleAxisd aa(geometry::polar_rotation(T.topLeftCorner<3, 3>()));
    r.emplace_back(aa.angle() * aa.axis());
  }
  return r;
}

Eigen::VectorXd region_log_scales(const HandleTransforms& transforms) {
  Eigen::VectorXd s(static_cast<Eigen::Index>(transforms.regions.size()));
  for (size_t h = 0; h < transforms.regions.size(); ++h)
    s[static_cast<Eigen::Index>(h)] =
        std::log(std::cbrt(std::abs(transforms.regions[h].topLeftCorner<3, 3>().determinant())));
  return s;
}

Eigen::Quaterniond blended_rotation(const RowWeights& weights, const std::vector<Eigen::Vector3d>& r) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (size_t h = 0; h < r.size(); ++h) sum += weights(static_cast<Eigen::Index>(h)) * r[h];
  const double angle = sum.norm();
  return angle > 0 ? Eigen::Quaterniond(Eigen::AngleAxisd(angle, sum / angle)) : Eigen::Quaterniond::Identity();
}

}  // namespace lapis::mesh_deform::detail
