// Private: the nearest rotation to a 3x3 matrix, fast enough to run once per vertex per
// iteration (ARAP's local step) or per frame (the implicit method's shearing removal, thesis
// §2.4.4). From the eigenvectors of AᵀA (closed form): R = Σ u_k v_kᵀ with u_k = A v_k / σ_k for
// the two largest singular values and the third pair completed by cross products, so the
// result is a proper rotation and needs no sign fix-up. ARAP's matrices are often nearly
// rank 2 (flat one-rings), which this handles exactly while iterative polar methods slow
// down. Cases where even σ_2 vanishes go to geometry's signed SVD.
#pragma once

#include <Eigen/Core>

namespace lapis::mesh_deform::detail {

// Rotation R maximizing tr(Rᵀ A): the rotation factor of A's polar decomposition when
// det A > 0, the closest proper rotation otherwise. fell_back  set when the SVD ran.
Eigen::Matrix3d nearest_rotation(const Eigen::Matrix3d& A, bool* fell_back = nullptr);

}  // namespace lapis::mesh_deform::detail
