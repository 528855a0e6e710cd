#include "lapis/hair_sketch/scalp_avoidance.h"

#include <algorithm>
#include <string>

#include "lapis/core/error.h"

namespace lapis::hair_sketch {
using hair_field::Constraint;
using hair_field::Field;
using hair_field::Grid;

std::vector<Constraint> scalp_avoidance_constraints(const Grid& grid, const Field& field, const Head& head,
                                                    const ScalpAvoidanceOptions& options) {
  if (field.rows() != grid.num_nodes())
    throw InvalidArgument("hair_sketch::scalp_avoidance_constraints(): field has " + std::to_string(field.rows()) +
                          " rows, grid " + std::to_string(grid.num_nodes()) + " nodes");
  const double band = options.band * grid.spacing;
  const Eigen::Vector3d lo = grid.to_grid(head.box.min()).array() - options.band - 1;
  const Eigen::Vector3d hi = grid.to_grid(head.box.max()).array() + options.band + 1;
  std::vector<int> nodes;
  for (int k = std::max(0, static_cast<int>(lo.z())); k <= std::min(grid.dims[2] - 1, static_cast<int>(hi.z())); ++k)
    for (int j = std::max(0, static_cast<int>(lo.y())); j <= std::min(grid.dims[1] - 1, static_cast<int>(hi.y())); ++j)
      for (int i = std::max(0, static_cast<int>(lo.x())); i <= std::min(grid.dims[0] - 1, static_cast<int>(hi.x()));
           ++i)
        nodes.push_back(grid.index(i, j, k));
  std::vector<char> keep(nodes.size(), 0);
  std::vector<Eigen::Vector3d> dirs(nodes.size());
#pragma omp parallel for schedule(dynamic, 256)
  for (int a = 0; a < static_cast<int>(nodes.size()); ++a) {
    const Eigen::Vector3d p = grid.position(nodes[a]);
    const auto c = head.bvh->closest_point(p);
    if (c.distance > band) continue;
    const Eigen::Vector3d n = head.face_normals.row(c.face).transpose();
    Eigen::Vector3d v = field.row(nodes[a]).transpose();
    if (v.dot(n) < 0) v -= v.dot(n) * n;  // inward: project on the tangent plane
    if (v.norm() < 1e-9) continue;
    dirs[a] = options.magnitude * v.normalized();
    keep[a] = 1;
  }
  std::vector<Constraint> out;
  for (size_t a = 0; a < nodes.size(); ++a)
    if (keep[a]) out.push_back({nodes[a], dirs[a]});
  return out;
}

}  // namespace lapis::hair_sketch
