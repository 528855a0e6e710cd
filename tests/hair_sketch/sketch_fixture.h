// Shared setup of the sketching tests: cameras (look-at + perspective, as the viewer's orbit
// camera makes them) and synthetic strokes from projecting known 3D paths.
#pragma once

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "fixture.h"
#include "lapis/geometry/camera.h"
#include "lapis/hair_sketch/sketch.h"

namespace hair_test {

inline lapis::geometry::CameraMatrices look_at(const Eigen::Vector3d& eye, const Eigen::Vector3d& target,
                                               const Eigen::Vector3d& up = Eigen::Vector3d::UnitY()) {
  return lapis::geometry::look_at_camera(eye, target, up);
}

inline Stroke project_path(const lapis::geometry::CameraMatrices& c, const std::vector<Eigen::Vector3d>& path) {
  Stroke s;
  for (const auto& p : path) s.push_back(lapis::geometry::project(c, p).head<2>());
  return s;
}

// The head surface point in direction d from the head centre (first hit from outside).
inline Eigen::Vector3d on_head(const Eigen::Vector3d& d) {
  const Head& h = bundled_head();
  const Eigen::Vector3d dir = d.normalized();
  const auto hit = h.bvh->intersect(h.center + 5 * dir, -dir);
  return hit->point;
}

// Distance from p to the polyline (nearest point over its segments).
inline double distance_to_path(const Eigen::Vector3d& p, const std::vector<Eigen::Vector3d>& poly) {
  double best = (p - poly.front()).norm();
  for (size_t i = 1; i < poly.size(); ++i) {
    const Eigen::Vector3d a = poly[i - 1], ab = poly[i] - a;
    const double t = ab.squaredNorm() > 0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
    best = std::min(best, (a + t * ab - p).norm());
  }
  return best;
}

// A scratch file path under the system temp directory.
inline std::filesystem::path temp_path(const std::string& dir, const std::string& name) {
  const std::filesystem::path d = std::filesystem::temp_directory_path() / dir;
  std::filesystem::create_directories(d);
  return d / name;
}

}  // namespace hair_test

#include "lapis/hair_sketch/document.h"
#include "lapis/hair_sketch/stroke_commands.h"
#include "lapis/hair_sketch/style_field.h"

namespace hair_test {

inline HairstyleSettings small_settings() {
  HairstyleSettings s;
  s.grid.target_unknowns = 6000;
  s.field_method = FieldMethod::Thesis;
  s.roots.count = 300;
  s.growth.max_length = 60;
  return s;
}

inline lapis::geometry::CameraMatrices right_camera() { return look_at({5, 1.5, -0.5}, {0, 0.4, -0.3}); }
inline lapis::geometry::CameraMatrices top_camera() { return look_at({0, 5, 0}, {0, 0, 0}, {0, 0, -1}); }

// A stroke over the head's surface in the plane through the centre spanned by `a` (start)
// and `b` (direction of travel), from angle 0 to `sweep`, then `beyond` more pixels.
inline Stroke surface_stroke(const lapis::geometry::CameraMatrices& cam, const Eigen::Vector3d& a,
                             const Eigen::Vector3d& b, double sweep, int beyond = 0) {
  std::vector<Eigen::Vector3d> p;
  for (int i = 0; i <= 20; ++i) {
    const double t = sweep * i / 20;
    p.push_back(on_head(std::cos(t) * a.normalized() + std::sin(t) * b.normalized()));
  }
  Stroke s = project_path(cam, p);
  const Eigen::Vector2d step = s.back() - s[s.size() - 2];
  for (int k = 0; k < beyond; ++k) s.push_back(s.back() + step);
  return s;
}

inline RecordedStroke recorded(StrokeAction a, const lapis::geometry::CameraMatrices& cam, std::vector<Stroke> strokes,
                               int target = -1) {
  RecordedStroke r;
  r.action = a;
  r.camera = cam;
  r.strokes = std::move(strokes);
  r.target = target;
  return r;
}

// The screen points of a document curve, from `from` to `to` (fractions of its points).
inline Stroke curve_on_screen(const lapis::geometry::CameraMatrices& cam, const std::vector<Eigen::Vector3d>& c,
                              double from, double to) {
  std::vector<Eigen::Vector3d> p;
  const int n = static_cast<int>(c.size()) - 1;
  for (int i = static_cast<int>(from * n); i <= static_cast<int>(to * n); ++i) p.push_back(c[i]);
  return project_path(cam, p);
}

}  // namespace hair_test
