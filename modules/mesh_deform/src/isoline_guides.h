// Private: rotations beyond π for the isolines model. A handle's matrix cannot tell 270° from
// −90°, and the isolines' affine transforms can unwind through shrunk in-between matrices, so
// a warm start alone loses the turn past π (the paper's limitation, §5: "requires specifying
// extra in-between handles"). As the implicit method does (rotation_guide.h), the angle of each
// region handle is unwrapped frame to frame; past guide_angle, the linear parts of its isoline
// set are pulled toward their share s_j of it: the in-between handles, placed on the isolines.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "isoline_basis.h"
#include "lapis/mesh_deform/deformer.h"
#include "lapis/mesh_deform/handle_fields.h"

namespace lapis::mesh_deform::detail {

struct IsolineGuides {
  std::vector<Eigen::Vector3d> angle;   // per region handle: rotation vector continued over the drag
  std::vector<char> guided;             // per isoline
  std::vector<Eigen::Matrix3d> target;  // per isoline: the guide's linear part (when guided)

  void reset(int region_handles, int isolines);
  // Unwraps this frame's handle rotations and places the guides; returns whether the set of
  // guided isolines changed (then the normal matrix must be refactorized).
  bool update(const HandleTransforms& t, const IsolineBasis& basis, const HandleSets& sets, double guide_angle);
};

}  // namespace lapis::mesh_deform::detail
