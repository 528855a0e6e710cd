#include "rotation_fit.h"

#include <cmath>

#include <Eigen/Eigenvalues>

#include "lapis/geometry/polar.h"

namespace lapis::mesh_deform::detail {
namespace {

// Newton's error after a step of length δ is at most about C δ², C ≈ ‖B‖ ‖H⁻¹‖ ≤ tr(B) tr(H⁻¹)
// (the Hessian's Lipschitz constant over its smallest eigenvalue), so the iteration stops once
// C δ² < kRoundingAngle: the step just taken left an error of rounding size, and no further
// step is needed to confirm it. A start more than a few steps away goes to the next start.
constexpr double kRoundingAngle = 1e-15;
constexpr int kMaxNewtonSteps = 6;

// n R for the quaternion q of squared norm n (any n > 0): the rotation matrix's quadratic
// form without the division, which every use below cancels.
Eigen::Matrix3d scaled_rotation(const Eigen::Quaterniond& q) {
  const double w = q.w(), x = q.x(), y = q.y(), z = q.z();
  const double ww = w * w, xx = x * x, yy = y * y, zz = z * z;
  const double xy = x * y, xz = x * z, yz = y * z, wx = w * x, wy = w * y, wz = w * z;
  Eigen::Matrix3d M;
  M << ww + xx - yy - zz, 2 * (xy - wz), 2 * (xz + wy),  //
      2 * (xy + wz), ww - xx + yy - zz, 2 * (yz - wx),   //
      2 * (xz - wy), 2 * (yz + wx), ww - xx - yy + zz;
  return M;
}

// The Newton step ω (R ← R exp([ω]×)) for f(R) = tr(Rᵀ A) at R, with B = Rᵀ A: the gradient is
// the skew part of B as a vector, g = (B32 − B23, B13 − B31, B21 − B12), and the Hessian is
// H = tr(B) I − (B + Bᵀ)/2, so ω = H⁻¹ g (solved by the adjugate: H is symmetric 3x3).
// error_gain is C above: the factor from the step's squared length to the error it leaves.
// False when H is not positive definite (Sylvester's leading minors): then R is not in the
// basin of the maximum. At a stationary point a positive definite H also certifies that the
// maximum is the global one: tr(Rᵀ A) has no other local maximum on SO(3).
// B may be given times any n > 0 (B = (n R)ᵀ A): ω and error_gain do not change.
bool newton_step(const Eigen::Matrix3d& B, Eigen::Vector3d& w, double& error_gain) {
  const Eigen::Vector3d g(B(2, 1) - B(1, 2), B(0, 2) - B(2, 0), B(1, 0) - B(0, 1));
  const double t = B.trace();
  const double h00 = t - B(0, 0), h11 = t - B(1, 1), h22 = t - B(2, 2);
  const double h01 = -0.5 * (B(0, 1) + B(1, 0)), h02 = -0.5 * (B(0, 2) + B(2, 0)), h12 = -0.5 * (B(1, 2) + B(2, 1));
  const double a00 = h11 * h22 - h12 * h12, a01 = h02 * h12 - h01 * h22, a02 = h01 * h12 - h02 * h11;
  const double a11 = h00 * h22 - h02 * h02, a12 = h01 * h02 - h00 * h12, a22 = h00 * h11 - h01 * h01;
  const double det = h00 * a00 + h01 * a01 + h02 * a02;
  if (!(h00 > 0 && a22 > 0 && det > 0)) return false;  // also false for NaN and overflow
  const double inv = 1 / det;
  error_gain = t * (a00 + a11 + a22) * inv;
  w = Eigen::Vector3d(a00 * g[0] + a01 * g[1] + a02 * g[2], a01 * g[0] + a11 * g[1] + a12 * g[2],
                      a02 * g[0] + a12 * g[1] + a22 * g[2]) *
      inv;
  return true;
}

// Newton's method from q; on success q and R hold the maximizer. The rotation is kept as a
// quaternion and each step applied as its Cayley rotation, quaternion (1, ω/2): a retraction,
// so convergence stays quadratic, and R never drifts from orthogonality however many
// iterations and frames warm-start from it. Between steps q is not normalized (a Cayley
// factor grows its norm by 1 + |ω|²/4, and the steps see only n R): the square root and the
// division are paid once, at the end, off the chain of dependent operations that bounds a
// step's latency.
bool newton_refine(const Eigen::Matrix3d& A, Eigen::Quaterniond& q, Eigen::Matrix3d& R) {
  Eigen::Quaterniond p = q;
  for (int step = 0; step < kMaxNewtonSteps; ++step) {
    Eigen::Vector3d w;
    double error_gain;
    if (!newton_step(scaled_rotation(p).transpose() * A, w, error_gain)) return false;
    p = p * Eigen::Quaterniond(1, 0.5 * w[0], 0.5 * w[1], 0.5 * w[2]);
    if (error_gain * w.squaredNorm() < kRoundingAngle) {
      q = p.normalized();
      R = q.toRotationMatrix();
      return true;
    }
  }
  return false;
}

// Closed-form estimate from the eigenvectors of AᵀA: R = Σ u_k v_kᵀ with u_k = A v_k / σ_k for
// the two largest singular values and the third pair completed by cross products, a proper
// rotation with no sign fix-up. Only a start: the eigenvectors of the squared matrix lose
// digits as σ2/σ1 falls (errors of 1e-2 at σ2/σ1 ≈ 1e-3 were seen). False when σ2/σ1 < 1e-6.
bool closed_form_rotation(const Eigen::Matrix3d& A, Eigen::Matrix3d& R) {
  const double scale = A.cwiseAbs().maxCoeff();
  if (!(scale > 0) || !std::isfinite(scale)) return false;
  const Eigen::Matrix3d B = A / scale;  // keeps AᵀA far from under/overflow
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
  es.computeDirect(B.transpose() * B);  // eigenvalues ascending: σ² of B
  const Eigen::Vector3d v1 = es.eigenvectors().col(2), v2 = es.eigenvectors().col(1);
  Eigen::Vector3d u1 = B * v1;
  const double n1 = u1.norm();
  Eigen::Vector3d u2 = B * v2;
  if (!(n1 > 0)) return false;
  u1 /= n1;
  u2 -= u1 * u1.dot(u2);  // re-orthogonalize: the eigenvectors carry rounding
  const double n2 = u2.norm();
  if (!(n2 > 1e-6 * n1)) return false;
  u2 /= n2;
  const Eigen::Vector3d v1n = v1.normalized();
  const Eigen::Vector3d v2n = (v2 - v1n * v1n.dot(v2)).normalized();
  R = u1 * v1n.transpose() + u2 * v2n.transpose() + u1.cross(u2) * v1n.cross(v2n).transpose();
  return true;
}

}  // namespace

Eigen::Matrix3d nearest_rotation(const Eigen::Matrix3d& A, Eigen::Quaterniond& q, bool* fell_back) {
  Eigen::Matrix3d R;
  if (newton_refine(A, q, R)) return R;
  if (closed_form_rotation(A, R)) {
    q = Eigen::Quaterniond(R);
    if (newton_refine(A, q, R)) return R;
  }
  // Rank < 2 (or a Hessian too ill-conditioned for Newton to settle): the maximizer is not
  // unique or barely so, and the SVD picks one.
  const double scale = A.cwiseAbs().maxCoeff();
  if (!(scale > 0) || !std::isfinite(scale)) {  // A = 0: every rotation is optimal
    q.setIdentity();
    return Eigen::Matrix3d::Identity();
  }
  if (fell_back) *fell_back = true;
  R = geometry::polar_rotation(A);
  q = Eigen::Quaterniond(R);
  return R;
}

Eigen::Matrix3d nearest_rotation(const Eigen::Matrix3d& A, bool* fell_back) {
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  return nearest_rotation(A, q, fell_back);
}

}  // namespace lapis::mesh_deform::detail
