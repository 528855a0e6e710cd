// Ponytail (thesis §4.5, Fig. 4.5 middle/right): a spine curve, a cross-section curve and
// two profile curves define circular cross sections along the spine between the profiles
// (C1 first, near the scalp; C2 last). Three kinds of constraints: longitudinal directions
// of the surface of revolution near the cross sections, spine tangents from C2 on, and
// centripetal constraints toward C1's centre in the annulus 1.3 r – 1.9 r on C1's plane,
// of magnitude = tightness. Where that annulus is thinner than a cell, the nodes nearest it
// are constrained too, so the ring has no gaps (docs/decisions.md).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "lapis/hair_field/constraints.h"
#include "lapis/hair_field/grid.h"

namespace lapis::hair_sketch {

struct Ponytail {
  std::vector<Eigen::Vector3d> spine;                 // from the head outward
  std::vector<Eigen::Vector3d> cross_section;         // a loop around the spine: C1's place and radius
  std::vector<Eigen::Vector3d> profile_a, profile_b;  // along the spine on either side: radii
  double tightness = 0.6;                             // centripetal magnitude (thesis §4.5 default)
  double inner_ratio = 1.3;                           // annulus R1 = 1.3 r (thesis §4.5)
  double outer_ratio = 1.9;                           // annulus R2 = 1.9 r (thesis §4.5)

  // The first cross section: centre, unit normal (spine direction), radius.
  struct Section {
    Eigen::Vector3d center, normal;
    double radius;
  };
  // Throws InvalidArgument for degenerate curves.
  Section first_section() const;

  std::vector<hair_field::Constraint> constraints(const hair_field::Grid& grid) const;
};

}  // namespace lapis::hair_sketch
