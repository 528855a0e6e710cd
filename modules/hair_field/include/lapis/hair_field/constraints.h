// Soft direction constraints t_i ≈ c_i of the field energy (thesis §4.4.1) and the diff
// between two constraint sets that drives the incremental solve (§4.4.2): added and removed
// nodes change the normal matrix' diagonal (WᵀW), target-only changes touch the
// right-hand side alone.
#pragma once

#include <span>
#include <vector>

#include <Eigen/Core>

namespace lapis::hair_field {

// Grid node `node` should carry `direction` (its length is the constraint's magnitude:
// 1 for curve tangents, fading in stream-curve tails, 0.3 / 0.6 for discontinuity,
// scalp and centripetal constraints).
struct Constraint {
  int node = 0;
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();
};

// At most one target per node, sorted by node: what the field solvers consume.
class ConstraintSet {
 public:
  ConstraintSet() = default;
  // Merges constraints from any number of primitives. Several targets on one node are
  // averaged (two curves crossing a cell agree on their mean direction). Throws
  // InvalidArgument for a negative node or a non-finite direction.
  static ConstraintSet merge(std::span<const std::vector<Constraint>> groups);
  static ConstraintSet from(const std::vector<Constraint>& constraints);

  const std::vector<Constraint>& items() const { return items_; }
  int size() const { return static_cast<int>(items_.size()); }
  bool empty() const { return items_.empty(); }
  // The target at node, or nullptr.
  const Eigen::Vector3d* find(int node) const;
  int max_node() const { return items_.empty() ? -1 : items_.back().node; }

 private:
  std::vector<Constraint> items_;
};

// What changed from one constraint set to the next.
struct ConstraintDiff {
  std::vector<Constraint> added;    // nodes newly constrained, with their targets
  std::vector<int> removed;         // nodes no longer constrained
  std::vector<Constraint> changed;  // still constrained, new target
  int weight_changes() const { return static_cast<int>(added.size() + removed.size()); }
  bool empty() const { return added.empty() && removed.empty() && changed.empty(); }
};

// Targets equal to within `tolerance` (absolute, per component) count as unchanged.
ConstraintDiff diff(const ConstraintSet& before, const ConstraintSet& after, double tolerance = 0.0);

}  // namespace lapis::hair_field
