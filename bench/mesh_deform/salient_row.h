// The salient method's row of bench_mesh_deform (Zhao et al. 2016, Table 1's quantities):
// detection stage by stage (eigenpairs at several k, clustering), the subspace at several
// sizes, location and C, Table 1's precomputation, the 5-iteration frame, peak memory, and the
// last frame's distortion and feature rigidity beside ARAP's at 5 iterations in the same run.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "lapis/mesh_deform/deformer.h"

namespace lapis::bench {

// m, sel and drag as the other rows use them; arap_iterations per ARAP frame.
nlohmann::json salient_row(const mesh_deform::TriMesh& m, const mesh_deform::Selection& sel,
                           const std::vector<Eigen::Matrix4d>& drag, int arap_iterations);

}  // namespace lapis::bench
