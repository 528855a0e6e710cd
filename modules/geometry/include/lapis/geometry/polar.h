// Small dense tools of the local steps of ARAP and implicit Laplacian editing: a fast 3x3
// SVD, polar rotation with the reflection fixed, the nearest rotation-times-uniform-scale
// (thesis §2.4.4), best similarity between point sets (Umeyama 1991), local frames.
#pragma once

#include <Eigen/Core>

namespace lapis::geometry {

// Signed ("rotation-variant") SVD: A = U diag(S) V^T with U and V proper rotations
// (det = +1), S(0) >= S(1) >= |S(2)|, and S(2) < 0 exactly when det(A) < 0. This is the
// form polar decomposition wants (McAdams et al. 2011, "Computing the SVD of 3x3 matrices
// with minimal branching"): the nearest rotation is U V^T with no sign fix-up. For the
// conventional SVD, negate S(2) and U's last column when S(2) < 0.
// Method: cyclic Jacobi on A^T A for V (3-4 sweeps), Givens QR of A V for U and S, and one
// Jacobi polish of the trailing 2x2 block, so that U S V^T reproduces A to ~1e-15 |A| even
// for nearly singular A. Faster than Eigen's JacobiSVD<Matrix3d>: see bench/geometry.
void svd3(const Eigen::Matrix3d& A, Eigen::Matrix3d& U, Eigen::Vector3d& S, Eigen::Matrix3d& V);

// The rotation nearest to M in the Frobenius norm (polar decomposition M = R P): U V^T of
// the signed SVD, a proper rotation even when det(M) <= 0.
Eigen::Matrix3d polar_rotation(const Eigen::Matrix3d& M);

// x -> s R x + t.
struct Similarity3 {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  double s = 1.0;
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  Eigen::Vector3d operator()(const Eigen::Vector3d& x) const { return s * (R * x) + t; }
  Eigen::Matrix3d linear() const { return s * R; }
};

// Shearing removal of thesis §2.4.4: with M = U W V^T, R = U V^T and
// s = sqrt((l1^2 + l2^2 + l3^2) / 3) for the singular values l. t is zero.
Similarity3 nearest_similarity(const Eigen::Matrix3d& M);

// Least-squares similarity mapping the rows of from onto the rows of to (Umeyama 1991,
// closed form; Horn 1987 for the rotation): minimizes sum_i |s R from_i + t - to_i|^2 with R
// a proper rotation. with_scale = false fixes s = 1 (rigid fit, Kabsch). Throws
// InvalidArgument for differing row counts, fewer than 1 point, or (with scale) when all
// from points coincide.
Similarity3 fit_similarity(const Eigen::MatrixX3d& from, const Eigen::MatrixX3d& to, bool with_scale = true);

// Right-handed orthonormal frame [t1 t2 n] (columns) with n = normal / |normal|; t1 is
// reference projected onto the tangent plane when that is well defined (|projection| >
// 1e-8 |reference|), else the branch-free basis of Duff et al. 2017 ("Building an
// orthonormal basis, revisited"). Throws InvalidArgument for a zero or non-finite normal.
Eigen::Matrix3d local_frame(const Eigen::Vector3d& normal);
Eigen::Matrix3d local_frame(const Eigen::Vector3d& normal, const Eigen::Vector3d& reference);

}  // namespace lapis::geometry
