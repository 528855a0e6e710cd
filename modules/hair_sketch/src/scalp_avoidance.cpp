#include "lapis/hair_sketch/scalp_avoidance.h"

#include <algorithm>
#include <string>

#include "lapis/core/error.h"

namespace lapis::hair_sketch {
using hair_field::Constraint;
using hair_field::Field;
using hair_field::Grid;

ScalpAvoidance::ScalpAvoidance(const Grid& grid, const Head& head, const ScalpAvoidanceOptions& options)
    : num_nodes_(grid.num_nodes()), magnitude_(options.magnitude) {
  const double band = options.band * grid.spacing;
  const Eigen::Vector3d lo = grid.to_grid(head.box.min()).array() - options.band - 1;
  const Eigen::Vector3d hi = grid.to_grid(head.box.max()).array() + options.band + 1;
  std::vector<int> candidates;
  for (int k = std::max(0, static_cast<int>(lo.z())); k <= std::min(grid.dims[2] - 1, static_cast<int>(hi.z())); ++k)
    for (int j = std::max(0, static_cast<int>(lo.y())); j <= std::min(grid.dims[1] - 1, static_cast<int>(hi.y())); ++j)
      for (int i = std::max(0, static_cast<int>(lo.x())); i <= std::min(grid.dims[0] - 1, static_cast<int>(hi.x()));
           ++i)
        candidates.push_back(grid.index(i, j, k));
  std::vector<char> near(candidates.size(), 0);
  std::vector<Eigen::Vector3d> normals(candidates.size());
#pragma omp parallel for schedule(dynamic, 256)
  for (int a = 0; a < static_cast<int>(candidates.size()); ++a) {
    const auto c = head.bvh->closest_point(grid.position(candidates[a]));
    if (c.distance > band) continue;
    normals[a] = head.face_normals.row(c.face).transpose();
    near[a] = 1;
  }
  for (size_t a = 0; a < candidates.size(); ++a)
    if (near[a]) nodes_.push_back(candidates[a]), normals_.push_back(normals[a]);
}

std::vector<Constraint> ScalpAvoidance::constraints(const Field& field) const {
  if (field.rows() != num_nodes_)
    throw InvalidArgument("hair_sketch::ScalpAvoidance::constraints(): field has " + std::to_string(field.rows()) +
                          " rows, grid " + std::to_string(num_nodes_) + " nodes");
  std::vector<Constraint> out;
  out.reserve(nodes_.size());
  for (size_t a = 0; a < nodes_.size(); ++a) {
    const Eigen::Vector3d& n = normals_[a];
    Eigen::Vector3d v = field.row(nodes_[a]).transpose();
    if (v.dot(n) < 0) v -= v.dot(n) * n;  // inward: project on the tangent plane
    if (v.norm() < 1e-9) continue;
    out.push_back({nodes_[a], magnitude_ * v.normalized()});
  }
  return out;
}

std::vector<Constraint> scalp_avoidance_constraints(const Grid& grid, const Field& field, const Head& head,
                                                    const ScalpAvoidanceOptions& options) {
  if (field.rows() != grid.num_nodes())
    throw InvalidArgument("hair_sketch::scalp_avoidance_constraints(): field has " + std::to_string(field.rows()) +
                          " rows, grid " + std::to_string(grid.num_nodes()) + " nodes");
  return ScalpAvoidance(grid, head, options).constraints(field);
}

}  // namespace lapis::hair_sketch
