#include "rotation_fit.h"

#include <cmath>

#include <Eigen/LU>
#include <Eigen/SVD>

namespace lapis::mesh_deform::detail {

Eigen::Matrix3d nearest_rotation_svd(const Eigen::Matrix3d& A) {
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(A, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d U = svd.matrixU();
  const Eigen::Matrix3d V = svd.matrixV();
  if ((U * V.transpose()).determinant() < 0) U.col(2) = -U.col(2);
  return U * V.transpose();
}


Eigen::Matrix3d nearest_rotation(const Eigen::Matrix3d& A, Eigen::Quaterniond& q, bool* fell_back) {
  const double scale = A.norm();
  if (!(scale > 0) || !std::isfinite(scale)) {
    q = Eigen::Quaterniond::Identity();
    return Eigen::Matrix3d::Identity();
  }
  // Polar factor of B = R₀ᵀ A by Higham's scaled Newton iteration X ← (γX + X⁻ᵀ/γ) / 2:
  // quadratic convergence, and B is close to symmetric positive definite when the warm start
  // R₀ is close, so two or three steps usually do. det B ≤ 0 has no rotation as polar factor
  // (the nearest rotation then differs from it) and goes to the SVD.
  const Eigen::Matrix3d R0 = q.toRotationMatrix();
  Eigen::Matrix3d X = R0.transpose() * A;
  if (X.determinant() > 1e-12 * scale * scale * scale) {
    for (int it = 0; it < 30; ++it) {
      const Eigen::Matrix3d Y = X.inverse().transpose();
      const double gamma = std::sqrt(std::sqrt(Y.squaredNorm() / X.squaredNorm()));
      const Eigen::Matrix3d Xn = 0.5 * (gamma * X + Y / gamma);
      const double change = (Xn - X).squaredNorm();
      X = Xn;
      if (change < 1e-26) {
        Eigen::Matrix3d R = R0 * X;
        q = Eigen::Quaterniond(R);
        q.normalize();
        // Re-orthonormalized through the quaternion: the next warm start stays a rotation.
        return q.toRotationMatrix();
      }
    }
  }
  if (fell_back) *fell_back = true;
  const Eigen::Matrix3d R = nearest_rotation_svd(A);
  q = Eigen::Quaterniond(R);
  return R;
}

}  // namespace lapis::mesh_deform::detail
