// Per-vertex distortion of a deformed mesh against its rest state, for colour maps: the same
// three measures metrics.h summarises over the whole mesh, spread onto the vertices so a user
// sees where the details stretch, shear or lose their size.
#pragma once

#include <Eigen/Core>

#include "lapis/geometry/tri_mesh.h"

namespace lapis::mesh_deform {

enum class DistortionField {
  EdgeLength,       // mean over the vertex's face edges of |‖ẽ‖/‖e‖ − 1|
  Angle,            // mean over the vertex's triangle corners of |θ̃ − θ|, radians
  LaplacianLength,  // |‖δ̃_i‖/‖δ_i‖ − 1| (cotangent weights on the rest mesh; 0 where ‖δ_i‖ ≈ 0)
};

const char* to_string(DistortionField f);

// rest, deformed  same faces, #V by 3 each. Returns #V values (0 at isolated vertices).
// Throws InvalidArgument "mesh_deform::vertex_distortion(): ..." when the vertex counts differ.
Eigen::VectorXd vertex_distortion(const geometry::TriMesh& rest, const geometry::Vertices& deformed,
                                  DistortionField field);

}  // namespace lapis::mesh_deform
