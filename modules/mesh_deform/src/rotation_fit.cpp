#include "rotation_fit.h"

#include <cmath>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "lapis/geometry/polar.h"

namespace lapis::mesh_deform::detail {

Eigen::Matrix3d nearest_rotation(const Eigen::Matrix3d& A, bool* fell_back) {
  const double scale = A.cwiseAbs().maxCoeff();
  if (!(scale > 0) || !std::isfinite(scale)) return Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d B = A / scale;  // keeps AᵀA far from under/overflow
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
  es.computeDirect(B.transpose() * B);  // eigenvalues ascending: σ² of B
  const Eigen::Vector3d v1 = es.eigenvectors().col(2), v2 = es.eigenvectors().col(1);
  Eigen::Vector3d u1 = B * v1;
  const double n1 = u1.norm();
  Eigen::Vector3d u2 = B * v2;
  if (n1 > 0) {
    u1 /= n1;
    u2 -= u1 * u1.dot(u2);  // re-orthogonalize: the eigenvectors carry rounding
    const double n2 = u2.norm();
    // σ₂/σ₁ below ~1e-6: the eigenvectors of the near-double-zero pair are unreliable.
    if (n2 > 1e-6 * n1) {
      u2 /= n2;
      const Eigen::Vector3d v1n = v1.normalized();
      const Eigen::Vector3d v2n = (v2 - v1n * v1n.dot(v2)).normalized();
      return u1 * v1n.transpose() + u2 * v2n.transpose() + u1.cross(u2) * v1n.cross(v2n).transpose();
    }
  }
  if (fell_back) *fell_back = true;
  return geometry::polar_rotation(A);
}

}  // namespace lapis::mesh_deform::detail
