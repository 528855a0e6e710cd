#include "rotation_guide.h"

#include <cmath>

#include <Eigen/Geometry>

namespace lapis::mesh_deform::detail {

Eigen::Vector3d unwrap_rotation(const Eigen::Matrix3d& R, const Eigen::Vector3d& previous) {
  const Eigen::AngleAxisd aa(R);
  const Eigen::Vector3d u = aa.axis();
  const double theta = aa.angle();
  if (theta < 1e-9) {
    // The identity: its axis is arbitrary, so the whole turns are counted along `previous`.
    const double p = previous.norm(), turns = std::round(p / (2 * M_PI));
    return turns > 0 ? Eigen::Vector3d(previous * (2 * M_PI * turns / p)) : Eigen::Vector3d::Zero();
  }
  // Every rotation vector of R is (θ + 2πk) u; the one nearest to `previous` minimizes
  // |(θ + 2πk) u − p|, i.e. k = round((u·p − θ) / 2π).
  const double k = std::round((u.dot(previous) - theta) / (2 * M_PI));
  return (theta + 2 * M_PI * k) * u;
}

Eigen::Matrix3d rotation_of(const Eigen::Vector3d& r) {
  const double a = r.norm();
  return a > 0 ? Eigen::AngleAxisd(a, r / a).toRotationMatrix() : Eigen::Matrix3d::Identity();
}

std::vector<std::pair<int, double>> level_bands(const Stencil& s, const Eigen::VectorXd& h,
                                                const std::vector<char>& eligible, int levels) {
  std::vector<std::pair<int, double>> out;
  std::vector<int> taken(static_cast<size_t>(s.size()), 0);
  for (int k = 1; k <= levels; ++k) {
    const double l = double(k) / (levels + 1);
    for (int i = 0; i < s.size(); ++i) {
      if (!eligible[i] || taken[i]) continue;
      for (int e = s.offsets[i]; e < s.offsets[i + 1]; ++e) {
        const int j = s.nbr[e];
        // The edge (i, j) crosses level l and i is the nearer end.
        if ((h(i) - l) * (h(j) - l) <= 0 && std::abs(h(i) - l) <= std::abs(h(j) - l)) {
          out.emplace_back(i, l);
          taken[i] = 1;
          break;
        }
      }
    }
  }
  return out;
}

}  // namespace lapis::mesh_deform::detail
