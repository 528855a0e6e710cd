#include "lapis/hair_sketch/gravity_prior.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "lapis/core/error.h"

namespace lapis::hair_sketch {
namespace {

void check(const GravityPriorOptions& o) {
  auto bad = [](const std::string& field, const std::string& why) {
    throw InvalidArgument("hair_sketch: GravityPriorOptions::" + field + " " + why);
  };
  if (!(o.strength >= 0) || !std::isfinite(o.strength)) bad("strength", "must be finite and not negative");
  if (o.stride < 1 || o.stride > 64) bad("stride", "must be in [1, 64]");
  if (o.clearance < 0 || o.clearance > 64) bad("clearance", "must be in [0, 64]");
  if (!(o.turn_distance > 0) || !std::isfinite(o.turn_distance)) bad("turn_distance", "must be positive and finite");
  if (!o.down.allFinite() || o.down.norm() < 1e-12) bad("down", "must be a finite non-zero direction");
}

}  // namespace

Eigen::Vector3d gravity_prior_direction(const Head& head, const Eigen::Vector3d& p, const GravityPriorOptions& o) {
  check(o);
  const Eigen::Vector3d down = o.down.normalized();
  const auto [normal, point] = head.closest(p);
  const double s = std::clamp((p - point).norm() / o.turn_distance, 0.0, 1.0);
  // Near the head: out along the normal, and down along the surface. The normal's share fades
  // as gravity takes over.
  const Eigen::Vector3d along_surface = down - down.dot(normal) * normal;
  const Eigen::Vector3d d = (1 - s) * (0.5 * normal + along_surface) + s * down;
  const double length = d.norm();
  return length > 1e-9 ? Eigen::Vector3d(d / length) : Eigen::Vector3d::Zero();
}

std::vector<hair_field::Constraint> gravity_prior_constraints(const Head& head, const hair_field::Grid& grid,
                                                              const GravityPriorOptions& o) {
  check(o);
  std::vector<hair_field::Constraint> out;
  if (o.strength == 0) return out;
  for (int k = 0; k < grid.dims[2]; k += o.stride)
    for (int j = 0; j < grid.dims[1]; j += o.stride)
      for (int i = 0; i < grid.dims[0]; i += o.stride) {
        const int node = grid.index(i, j, k);
        const Eigen::Vector3d p = grid.position(node);
        if (head.inside(p)) continue;
        const Eigen::Vector3d d = gravity_prior_direction(head, p, o);
        if (d.squaredNorm() > 0) out.push_back({node, o.strength * d});
      }
  return out;
}

std::vector<hair_field::Constraint> prior_away_from(const std::vector<hair_field::Constraint>& prior,
                                                    const hair_field::ConstraintSet& sketched,
                                                    const hair_field::Grid& grid, int clearance) {
  if (prior.empty() || sketched.empty()) return prior;
  // Mark the box of `clearance` nodes around each sketched node.
  std::vector<char> near(static_cast<size_t>(grid.num_nodes()), 0);
  for (const auto& c : sketched.items()) {
    const auto ijk = grid.coords(c.node);
    int lo[3], hi[3];
    for (int a = 0; a < 3; ++a)
      lo[a] = std::max(0, ijk[a] - clearance), hi[a] = std::min(grid.dims[a] - 1, ijk[a] + clearance);
    for (int k = lo[2]; k <= hi[2]; ++k)
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int i = lo[0]; i <= hi[0]; ++i) near[static_cast<size_t>(grid.index(i, j, k))] = 1;
  }
  std::vector<hair_field::Constraint> out;
  for (const auto& c : prior)
    if (!near[static_cast<size_t>(c.node)]) out.push_back(c);
  return out;
}

hair_field::ConstraintSet with_prior(const hair_field::ConstraintSet& constraints,
                                     const std::vector<hair_field::Constraint>& prior) {
  if (prior.empty()) return constraints;
  std::vector<hair_field::Constraint> all = constraints.items();
  for (const auto& c : prior)
    if (!constraints.find(c.node)) all.push_back(c);
  return hair_field::ConstraintSet::from(all);
}

}  // namespace lapis::hair_sketch
