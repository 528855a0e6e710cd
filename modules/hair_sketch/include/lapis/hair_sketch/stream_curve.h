// Stream curve (thesis §4.5, Fig. 4.5 left): the general flow direction. Each segment of
// the curve, resampled at one grid spacing, constrains its neighbouring grid nodes to the
// segment's tangent; an optional extrapolated tail of a few segments fades from 1 to 0 so
// that hair stops near the curve's end.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "lapis/hair_field/constraints.h"
#include "lapis/hair_field/grid.h"

namespace lapis::hair_sketch {

struct StreamCurve {
  std::vector<Eigen::Vector3d> points;  // polyline, from the scalp outward
  int tail_segments = 0;                // thesis §4.5: optional "few extra segments" fading 1 → 0

  // Throws InvalidArgument for fewer than 2 points, non-finite or zero-length curves.
  std::vector<hair_field::Constraint> constraints(const hair_field::Grid& grid) const;
};

}  // namespace lapis::hair_sketch
