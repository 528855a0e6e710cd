// Scalp-penetration avoidance (thesis §4.6), a one-shot step once a style is satisfactory:
// grid nodes near the head whose direction points inward get it projected onto the tangent
// plane of the nearest surface point, and all near-surface nodes become constraints of
// small magnitude (0.3) so their global influence stays low.
#pragma once

#include <vector>

#include "lapis/hair_field/constraints.h"
#include "lapis/hair_field/grid.h"
#include "lapis/hair_field/grid_operators.h"
#include "lapis/hair_sketch/head.h"

namespace lapis::hair_sketch {

struct ScalpAvoidanceOptions {
  double band = 1.5;       // "near the scalp": within this many grid spacings of the head
  double magnitude = 0.3;  // thesis §4.6
};

// Constraints from the current field (n by 3 on grid). Nodes just inside the surface are
// included: trilinear lookups just outside it read them. Nodes with a vanishing direction
// are left free.
std::vector<hair_field::Constraint> scalp_avoidance_constraints(const hair_field::Grid& grid,
                                                                const hair_field::Field& field, const Head& head,
                                                                const ScalpAvoidanceOptions& options = {});

}  // namespace lapis::hair_sketch
