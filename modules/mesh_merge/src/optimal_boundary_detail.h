// Shared between the optimal boundary's set-up, search and merge.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace lapis::mesh_merge::detail {

// Throws InvalidArgument "mesh_merge::optimal_boundary(): <what>".
[[noreturn]] void fail_optimal(const std::string& what);

// The loop running counter-clockwise in uv (the conformal map keeps orientation, so that is with
// Ωf on its left, as ∂Ω0 runs), rotated to start at its lowest vertex index.
std::vector<int> canonical_loop(std::vector<int> loop, const Eigen::MatrixX2d& uv);

}  // namespace lapis::mesh_merge::detail
