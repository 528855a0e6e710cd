// Private: the nearest rotation to a 3x3 matrix, fast enough to run once per vertex per
// frame (ARAP's local step, the implicit method's shearing removal, thesis §2.4.4).
// Warm-started: the previous frame's rotation R₀ is almost the answer, so the polar factor of
// R₀ᵀA (near the identity) takes Newton's iteration two or three steps; a reflection (det ≤ 0)
// falls back to an SVD.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace lapis::mesh_deform::detail {

// Rotation R maximizing tr(Rᵀ A), i.e. the rotation factor of A's polar decomposition when
// det A > 0 (and the closest proper rotation otherwise). q  warm start in, result out;
// fell_back  set when the SVD fallback ran.
Eigen::Matrix3d nearest_rotation(const Eigen::Matrix3d& A, Eigen::Quaterniond& q, bool* fell_back = nullptr);

// Reference: R = U Vᵀ from Eigen's JacobiSVD with the sign of the smallest singular vector
// flipped when det < 0. Used as the fallback and by tests.
Eigen::Matrix3d nearest_rotation_svd(const Eigen::Matrix3d& A);

}  // namespace lapis::mesh_deform::detail
