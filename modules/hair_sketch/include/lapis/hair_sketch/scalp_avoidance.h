// Scalp-penetration avoidance (thesis §4.6), a one-shot step once a style is satisfactory:
// grid nodes near the head whose direction points inward get it projected onto the tangent
// plane of the nearest surface point, and all near-surface nodes become constraints of
// small magnitude (0.3) so their global influence stays low.
#pragma once

#include <cstdint>
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

// The nodes near the head and the normals there depend on the grid and the head only, and
// finding them (a closest-point query per node of the head's box) costs far more than the
// projection itself: an interactive loop finds them once and projects per edit.
class ScalpAvoidance {
 public:
  ScalpAvoidance(const hair_field::Grid& grid, const Head& head, const ScalpAvoidanceOptions& options = {});
  // Constraints from the current field (n by 3 on the grid). Nodes just inside the surface are
  // included: trilinear lookups just outside it read them. Nodes with a vanishing direction
  // are left free.
  std::vector<hair_field::Constraint> constraints(const hair_field::Field& field) const;
  int near_nodes() const { return static_cast<int>(nodes_.size()); }

 private:
  std::int64_t num_nodes_ = 0;
  double magnitude_ = 0;
  std::vector<int> nodes_;                // within the band, by index
  std::vector<Eigen::Vector3d> normals_;  // the head's at each one's closest point
};

// ScalpAvoidance(grid, head, options).constraints(field), for one-shot use.
std::vector<hair_field::Constraint> scalp_avoidance_constraints(const hair_field::Grid& grid,
                                                                const hair_field::Field& field, const Head& head,
                                                                const ScalpAvoidanceOptions& options = {});

}  // namespace lapis::hair_sketch
