#include "lapis/geometry/polar.h"

#include <Eigen/Geometry>
#include <cmath>
#include <string>

#include "lapis/core/error.h"

namespace lapis::geometry {
namespace {

// One Jacobi rotation in the (p, q) plane that zeroes S(p, q) of the symmetric S; V
// accumulates the rotations (Golub & Van Loan, Alg. 8.5.1; the stable tangent formula).
inline void jacobi_rotate(Eigen::Matrix3d& S, Eigen::Matrix3d& V, int p, int q) {
  const double spq = S(p, q);
  if (spq == 0) return;
  const double tau = (S(q, q) - S(p, p)) / (2 * spq);
  const double t = (tau >= 0 ? 1.0 : -1.0) / (std::abs(tau) + std::sqrt(1 + tau * tau));
  const double c = 1 / std::sqrt(1 + t * t), s = t * c;
  const int r = 3 - p - q;
  const double srp = S(r, p), srq = S(r, q);
  S(p, p) -= t * spq;
  S(q, q) += t * spq;
  S(p, q) = S(q, p) = 0;
  S(r, p) = S(p, r) = c * srp - s * srq;
  S(r, q) = S(q, r) = s * srp + c * srq;
  for (int i = 0; i < 3; ++i) {
    const double vp = V(i, p), vq = V(i, q);
    V(i, p) = c * vp - s * vq;
    V(i, q) = s * vp + c * vq;
  }
}

// Rotation in rows (p, q) of B that zeroes B(q, col); U accumulates its transpose.
inline void givens_zero(Eigen::Matrix3d& B, Eigen::Matrix3d& U, int p, int q, int col) {
  const double a = B(p, col), b = B(q, col);
  // sqrt(a^2 + b^2) is several times faster than std::hypot; hypot only where it would
  // overflow or underflow.
  double r = std::sqrt(a * a + b * b);
  if (!(r < 1e150) || r < 1e-150) r = std::hypot(a, b);
  if (r == 0) return;
  const double c = a / r, s = b / r;
  for (int j = 0; j < 3; ++j) {
    const double bp = B(p, j), bq = B(q, j);
    B(p, j) = c * bp + s * bq;
    B(q, j) = -s * bp + c * bq;
  }
  B(q, col) = 0;
  for (int i = 0; i < 3; ++i) {
    const double up = U(i, p), uq = U(i, q);
    U(i, p) = c * up + s * uq;
    U(i, q) = -s * up + c * uq;
  }
}

// Swaps columns i and j of B and V, negating one so that det(V) stays +1.
inline void swap_columns(Eigen::Matrix3d& B, Eigen::Matrix3d& V, Eigen::Vector3d& norms, int i, int j) {
  B.col(i).swap(B.col(j));
  V.col(i).swap(V.col(j));
  B.col(j) = -B.col(j);
  V.col(j) = -V.col(j);
  std::swap(norms[i], norms[j]);
}

// Swaps singular pair i, j (columns of U and V, entries of S) keeping U, V proper rotations.
inline void swap_pairs(Eigen::Matrix3d& U, Eigen::Vector3d& S, Eigen::Matrix3d& V, int i, int j) {
  U.col(i).swap(U.col(j));
  V.col(i).swap(V.col(j));
  U.col(j) = -U.col(j);
  V.col(j) = -V.col(j);
  std::swap(S[i], S[j]);  // column j of U and of V both negated: S[j] keeps its sign
}

// Restores S(0) >= S(1) >= |S(2)| (with S(1) >= 0) after rounding ties or the polish step.
inline void order_singular_values(Eigen::Matrix3d& U, Eigen::Vector3d& S, Eigen::Matrix3d& V) {
  for (int pass = 0; pass < 2; ++pass) {
    if (S[0] < S[1]) swap_pairs(U, S, V, 0, 1);
    if (S[1] < std::abs(S[2])) {
      swap_pairs(U, S, V, 1, 2);
      if (S[1] < 0) {  // move the sign back to the last value: negate U's columns 1 and 2
        S[1] = -S[1], S[2] = -S[2];
        U.col(1) = -U.col(1), U.col(2) = -U.col(2);
      }
    }
  }
}

}  // namespace

void svd3(const Eigen::Matrix3d& A, Eigen::Matrix3d& U, Eigen::Vector3d& S, Eigen::Matrix3d& V) {
  Eigen::Matrix3d sym = A.transpose() * A;
  V.setIdentity();
  // Cyclic Jacobi converges quadratically: 4-5 sweeps reach rounding level for doubles.
  for (int sweep = 0; sweep < 12; ++sweep) {
    const double off = sym(0, 1) * sym(0, 1) + sym(0, 2) * sym(0, 2) + sym(1, 2) * sym(1, 2);
    const double diag = sym(0, 0) * sym(0, 0) + sym(1, 1) * sym(1, 1) + sym(2, 2) * sym(2, 2);
    if (off <= 1e-30 * diag) break;  // off-diagonal at ~1e-15 relative: rounding level
    jacobi_rotate(sym, V, 0, 1);
    jacobi_rotate(sym, V, 0, 2);
    jacobi_rotate(sym, V, 1, 2);
  }
  Eigen::Matrix3d B = A * V;
  Eigen::Vector3d norms = B.colwise().squaredNorm();
  if (norms[0] < norms[1]) swap_columns(B, V, norms, 0, 1);
  if (norms[0] < norms[2]) swap_columns(B, V, norms, 0, 2);
  if (norms[1] < norms[2]) swap_columns(B, V, norms, 1, 2);
  U.setIdentity();
  givens_zero(B, U, 0, 1, 0);
  givens_zero(B, U, 0, 2, 0);
  givens_zero(B, U, 1, 2, 1);
  // Polish the trailing 2x2 block. A^T A rounds at eps S(0)^2, which leaves B(1, 2) at about
  // eps S(0)^2 / S(1): large when S(1) << S(0). One Jacobi rotation of that block's own
  // normal matrix (entries of size S(1)^2, no S(0) involved) and a Givens re-triangulation
  // bring it to eps S(1).
  if (B(1, 2) != 0) {
    const double a = B(1, 1), b = B(1, 2), d = B(2, 2);
    const double spq = a * b, tau = (b * b + d * d - a * a) / (2 * spq);
    const double t = (tau >= 0 ? 1.0 : -1.0) / (std::abs(tau) + std::sqrt(1 + tau * tau));
    const double c = 1 / std::sqrt(1 + t * t), s = t * c;
    if (std::isfinite(t))
      for (int i = 0; i < 3; ++i) {
        const double bp = B(i, 1), bq = B(i, 2), vp = V(i, 1), vq = V(i, 2);
        B(i, 1) = c * bp - s * bq, B(i, 2) = s * bp + c * bq;
        V(i, 1) = c * vp - s * vq, V(i, 2) = s * vp + c * vq;
      }
    givens_zero(B, U, 1, 2, 1);
  }
  // Each Givens step leaves a non-negative hypot on the diagonal, so S(0), S(1) >= 0 and the
  // sign of det(A) lands in S(2).
  S << B(0, 0), B(1, 1), B(2, 2);
  order_singular_values(U, S, V);
}

Eigen::Matrix3d polar_rotation(const Eigen::Matrix3d& M) {
  Eigen::Matrix3d U, V;
  Eigen::Vector3d S;
  svd3(M, U, S, V);
  return U * V.transpose();
}

Similarity3 nearest_similarity(const Eigen::Matrix3d& M) {
  Eigen::Matrix3d U, V;
  Eigen::Vector3d S;
  svd3(M, U, S, V);
  Similarity3 out;
  out.R = U * V.transpose();
  out.s = std::sqrt(S.squaredNorm() / 3);
  return out;
}

Similarity3 fit_similarity(const Eigen::MatrixX3d& from, const Eigen::MatrixX3d& to, bool with_scale) {
  constexpr const char* fn = "geometry::fit_similarity()";
  if (from.rows() != to.rows() || from.rows() < 1)
    throw InvalidArgument(std::string(fn) + ": " + std::to_string(from.rows()) + " and " + std::to_string(to.rows()) +
                          " points, expected the same number, at least 1");
  const double n = static_cast<double>(from.rows());
  const Eigen::RowVector3d mu_x = from.colwise().mean(), mu_y = to.colwise().mean();
  const Eigen::MatrixX3d x = from.rowwise() - mu_x, y = to.rowwise() - mu_y;
  const Eigen::Matrix3d cov = y.transpose() * x / n;  // Umeyama's Sigma_xy
  Eigen::Matrix3d U, V;
  Eigen::Vector3d D;
  svd3(cov, U, D, V);
  Similarity3 out;
  out.R = U * V.transpose();  // the signed SVD already applies Umeyama's S = diag(1, 1, -1)
  if (with_scale) {
    const double var_x = x.squaredNorm() / n;
    if (!(var_x > 0)) throw InvalidArgument(std::string(fn) + ": all source points coincide, the scale is undefined");
    out.s = D.sum() / var_x;
  }
  out.t = mu_y.transpose() - out.s * out.R * mu_x.transpose();
  return out;
}

Eigen::Matrix3d local_frame(const Eigen::Vector3d& normal) {
  if (!normal.allFinite() || normal.squaredNorm() == 0)
    throw InvalidArgument("geometry::local_frame(): normal is zero or not finite");
  const Eigen::Vector3d n = normal.normalized();
  const double sign = std::copysign(1.0, n.z());
  const double a = -1.0 / (sign + n.z()), b = n.x() * n.y() * a;
  Eigen::Matrix3d frame;
  frame.col(0) << 1 + sign * n.x() * n.x() * a, sign * b, -sign * n.x();
  frame.col(1) << b, sign + n.y() * n.y() * a, -n.y();
  frame.col(2) = n;
  return frame;
}

Eigen::Matrix3d local_frame(const Eigen::Vector3d& normal, const Eigen::Vector3d& reference) {
  Eigen::Matrix3d frame = local_frame(normal);
  const Eigen::Vector3d n = frame.col(2);
  const Eigen::Vector3d t = reference - reference.dot(n) * n;
  if (t.allFinite() && t.norm() > 1e-8 * reference.norm()) {
    frame.col(0) = t.normalized();
    frame.col(1) = n.cross(frame.col(0));
  }
  return frame;
}

}  // namespace lapis::geometry
