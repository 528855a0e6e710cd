// Private: large handle rotations for implicit Laplacian editing. A rotation matrix cannot
// tell 270° from −90°, and the implicit method picks the smaller angle (thesis §2.5: "our
// system does not support editing with rotation angles larger than π ... one possible way is
// to use more handles such that rotation angles between successive handles is smaller than
// π"). Handles here carry transforms over a drag, so the angle accumulated frame by frame is
// known; this file unwraps it and places the "more handles" automatically: guide
// transformation constraints on level-set bands of a smooth field that is 0 at the fixed
// region and 1 at the handle, each band turned by its share of the accumulated rotation.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "stencil.h"

namespace lapis::mesh_deform::detail {

// Rotation vector (axis · angle) of R that is closest to `previous`: the angle is continued
// past π instead of wrapping around.
Eigen::Vector3d unwrap_rotation(const Eigen::Matrix3d& R, const Eigen::Vector3d& previous);

// Rotation matrix of rotation vector r.
Eigen::Matrix3d rotation_of(const Eigen::Vector3d& r);

// For levels ℓ_k = k / (levels + 1), k = 1..levels: the eligible vertices closest to where
// the field h crosses ℓ_k along an edge. Returns (vertex, level) pairs, each vertex once.
std::vector<std::pair<int, double>> level_bands(const Stencil& s, const Eigen::VectorXd& h,
                                                const std::vector<char>& eligible, int levels);

}  // namespace lapis::mesh_deform::detail
