// The polylines that show a style primitive on screen (and that selection clicks hit).
#pragma once

#include <vector>

#include "lapis/hair_sketch/document.h"

namespace lapis::hair_app {

inline std::vector<std::vector<Eigen::Vector3d>> primitive_polylines(const hair_sketch::StylePrimitive& p) {
  using namespace lapis::hair_sketch;
  if (const auto* s = std::get_if<StreamCurve>(&p.shape)) return {s->points};
  if (const auto* d = std::get_if<DividingCurve>(&p.shape)) return {d->points};
  const auto& t = std::get<Ponytail>(p.shape);
  return {t.spine, t.cross_section, t.profile_a, t.profile_b};
}

// The curve that hint strokes edit: a stream curve's points, a ponytail's spine.
inline const std::vector<Eigen::Vector3d>* editable_curve(const hair_sketch::StylePrimitive& p) {
  using namespace lapis::hair_sketch;
  if (const auto* s = std::get_if<StreamCurve>(&p.shape)) return &s->points;
  if (const auto* d = std::get_if<DividingCurve>(&p.shape)) return &d->points;
  return &std::get<Ponytail>(p.shape).spine;
}

}  // namespace lapis::hair_app
