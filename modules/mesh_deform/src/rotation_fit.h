// Private: the nearest rotation to a 3x3 matrix, fast enough to run once per vertex per
// iteration (ARAP's local step) or per frame (the implicit method's shearing removal, thesis
// §2.4.4). Both loops fit nearly the same rotation again and again, so the fast path is
// Newton's method on SO(3) started from the vertex's previous rotation: one to three steps of
// about a hundred flops reach the maximum of tr(Rᵀ A) to rounding, where a closed form pays
// for transcendental functions (and loses digits when A is nearly rank 2) and a 3x3 SVD for
// its sweeps. Without a usable start, a closed-form estimate from the eigenvectors of AᵀA
// starts Newton instead; geometry's signed SVD takes what Newton cannot (rank < 2).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace lapis::mesh_deform::detail {

// Rotation R maximizing tr(Rᵀ A): the rotation factor of A's polar decomposition when
// det A > 0, the closest proper rotation otherwise. fell_back is set when the SVD ran.
Eigen::Matrix3d nearest_rotation(const Eigen::Matrix3d& A, bool* fell_back = nullptr);

// The same rotation, found from the guess q (a unit quaternion: last iteration's or last
// frame's rotation of the same vertex), which is replaced by the result's quaternion. Any
// guess gives the same result to rounding; a near one only makes it faster.
Eigen::Matrix3d nearest_rotation(const Eigen::Matrix3d& A, Eigen::Quaterniond& q, bool* fell_back = nullptr);

}  // namespace lapis::mesh_deform::detail
