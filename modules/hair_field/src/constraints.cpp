#include "lapis/hair_field/constraints.h"

#include <algorithm>
#include <string>

#include "lapis/core/error.h"

namespace lapis::hair_field {

ConstraintSet ConstraintSet::merge(std::span<const std::vector<Constraint>> groups) {
  std::vector<Constraint> all;
  for (const auto& g : groups) {
    for (const auto& c : g) {
      if (c.node < 0)
        throw InvalidArgument("hair_field::ConstraintSet::merge(): negative node " + std::to_string(c.node));
      if (!c.direction.allFinite())
        throw InvalidArgument("hair_field::ConstraintSet::merge(): non-finite direction at node " +
                              std::to_string(c.node));
    }
    all.insert(all.end(), g.begin(), g.end());
  }
  // Stable so that the average is independent of nothing but the input order's grouping.
  std::stable_sort(all.begin(), all.end(), [](const Constraint& a, const Constraint& b) { return a.node < b.node; });
  ConstraintSet s;
  for (size_t i = 0; i < all.size();) {
    size_t j = i;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (; j < all.size() && all[j].node == all[i].node; ++j) sum += all[j].direction;
    s.items_.push_back({all[i].node, sum / static_cast<double>(j - i)});
    i = j;
  }
  return s;
}

ConstraintSet ConstraintSet::from(const std::vector<Constraint>& constraints) {
  return merge(std::span<const std::vector<Constraint>>(&constraints, 1));
}

const Eigen::Vector3d* ConstraintSet::find(int node) const {
  auto it = std::lower_bound(items_.begin(), items_.end(), node, [](const Constraint& c, int n) { return c.node < n; });
  return it != items_.end() && it->node == node ? &it->direction : nullptr;
}

ConstraintDiff diff(const ConstraintSet& before, const ConstraintSet& after, double tolerance) {
  ConstraintDiff d;
  const auto& a = before.items();
  const auto& b = after.items();
  size_t i = 0, j = 0;
  while (i < a.size() || j < b.size()) {
    if (j == b.size() || (i < a.size() && a[i].node < b[j].node)) {
      d.removed.push_back(a[i++].node);
    } else if (i == a.size() || b[j].node < a[i].node) {
      d.added.push_back(b[j++]);
    } else {
      if ((a[i].direction - b[j].direction).cwiseAbs().maxCoeff() > tolerance) d.changed.push_back(b[j]);
      ++i, ++j;
    }
  }
  return d;
}

}  // namespace lapis::hair_field
