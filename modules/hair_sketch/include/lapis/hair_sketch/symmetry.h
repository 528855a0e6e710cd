// Symmetric sketching: a primitive marked `mirrored` brings its mirror image across the head's
// sagittal plane (x = head.center.x: the bundled head faces +z with y up) into the style. The
// twin is derived, not stored, so editing the primitive edits its twin and undo removes both.
// The field's grid is centred on the head's box, hence symmetric about that plane, so the
// twin's constraints sit on the mirrored nodes.
#pragma once

#include <vector>

#include "lapis/hair_field/constraints.h"
#include "lapis/hair_field/grid.h"
#include "lapis/hair_sketch/document.h"

namespace lapis::hair_sketch {

// The mirror image of a point across the plane x = plane_x.
inline Eigen::Vector3d mirror_point(const Eigen::Vector3d& p, double plane_x) {
  return {2 * plane_x - p.x(), p.y(), p.z()};
}

// p's shape and viewpoint mirrored across x = plane_x; a dividing curve's tilts change sign,
// since mirroring turns a left-hand tilt into a right-hand one. The result is not mirrored.
StylePrimitive mirror_image(const StylePrimitive& p, double plane_x);

// The constraints mirrored across the grid's own mid-plane in x: node (i, j, k) to
// (dims[0] − 1 − i, j, k), direction (x, y, z) to (−x, y, z). What the test of the twin's
// constraints compares against.
std::vector<hair_field::Constraint> mirror_constraints(const std::vector<hair_field::Constraint>& c,
                                                       const hair_field::Grid& grid);

}  // namespace lapis::hair_sketch
