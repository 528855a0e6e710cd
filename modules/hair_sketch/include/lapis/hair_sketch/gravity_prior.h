// A weak default for the field where nothing is sketched. The thesis' energy (Eq. 4.1) only
// smooths between the user's constraints, so one stream curve, or a dividing curve alone,
// carries its direction to the whole grid and the hair leaves the head as a sideways sheet.
// The prior adds what users expect when nothing says otherwise: hair leaves the scalp along
// its normal and turns down under gravity. It is a sparse lattice of short constraints (one
// node per stride³ block, target length `strength`, against 1 for the user's curve tangents),
// never on or near a node the user's primitives constrain (within `clearance` nodes), so
// wherever the user sketched, the user's curves decide. Off by default: the thesis' field
// exactly.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "lapis/hair_field/constraints.h"
#include "lapis/hair_field/grid.h"
#include "lapis/hair_sketch/head.h"

namespace lapis::hair_sketch {

struct GravityPriorOptions {
  double strength = 0;         // the targets' length; 0: no prior (the thesis' field)
  int stride = 3;              // one constrained node per stride × stride × stride block
  int clearance = 3;           // no prior within this many nodes (per axis) of a sketched one
  double turn_distance = 0.4;  // head units (the bundled head is about 2 tall) over which the
                               // direction turns from the scalp's normal to straight down
  Eigen::Vector3d down{0, -1, 0};
};

// The prior's direction at p (unit length, or zero where the turn passes through it): at the
// head, its outward normal plus gravity's part along the surface (hair combed down the head);
// from turn_distance on, straight down. Throws InvalidArgument for bad options.
Eigen::Vector3d gravity_prior_direction(const Head& head, const Eigen::Vector3d& p, const GravityPriorOptions& options);

// The prior's constraints on the grid: on every stride-th node along each axis that lies
// outside the head. Empty when strength is 0.
std::vector<hair_field::Constraint> gravity_prior_constraints(const Head& head, const hair_field::Grid& grid,
                                                              const GravityPriorOptions& options);

// The prior's constraints farther than `clearance` nodes (per axis) from every node `sketched`
// constrains: around a curve, the curve alone steers the field.
std::vector<hair_field::Constraint> prior_away_from(const std::vector<hair_field::Constraint>& prior,
                                                    const hair_field::ConstraintSet& sketched,
                                                    const hair_field::Grid& grid, int clearance);

// `constraints` plus the prior's where the user's leave a node free (no averaging with them).
hair_field::ConstraintSet with_prior(const hair_field::ConstraintSet& constraints,
                                     const std::vector<hair_field::Constraint>& prior);

}  // namespace lapis::hair_sketch
