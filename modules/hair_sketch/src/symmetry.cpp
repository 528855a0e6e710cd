#include "lapis/hair_sketch/symmetry.h"

namespace lapis::hair_sketch {
namespace {

void mirror_points(std::vector<Eigen::Vector3d>& points, double plane_x) {
  for (auto& p : points) p = mirror_point(p, plane_x);
}

}  // namespace

StylePrimitive mirror_image(const StylePrimitive& p, double plane_x) {
  StylePrimitive m = p;
  m.mirrored = false;
  m.viewpoint = mirror_point(p.viewpoint, plane_x);
  if (auto* s = std::get_if<StreamCurve>(&m.shape)) {
    mirror_points(s->points, plane_x);
  } else if (auto* d = std::get_if<DividingCurve>(&m.shape)) {
    mirror_points(d->points, plane_x);
    d->alpha0 = -d->alpha0;
    d->alpha1 = -d->alpha1;
  } else {
    auto& t = std::get<Ponytail>(m.shape);
    for (auto* curve : {&t.spine, &t.cross_section, &t.profile_a, &t.profile_b}) mirror_points(*curve, plane_x);
  }
  return m;
}

std::vector<hair_field::Constraint> mirror_constraints(const std::vector<hair_field::Constraint>& c,
                                                       const hair_field::Grid& grid) {
  std::vector<hair_field::Constraint> out;
  out.reserve(c.size());
  for (const auto& k : c) {
    const auto ijk = grid.coords(k.node);
    out.push_back({grid.index(grid.dims[0] - 1 - ijk[0], ijk[1], ijk[2]),
                   Eigen::Vector3d(-k.direction.x(), k.direction.y(), k.direction.z())});
  }
  return out;
}

}  // namespace lapis::hair_sketch
