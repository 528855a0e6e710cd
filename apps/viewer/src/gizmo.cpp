#include "lapis/viewer/gizmo.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace lapis::viewer {
namespace {

using geometry::CameraMatrices;

Eigen::Vector3d unit_axis(int a) { return Eigen::Vector3d::Unit(a); }

// Screen angle of p around c with y pointing up, so counter-clockwise on screen is positive.
double screen_angle(const Eigen::Vector2d& p, const Eigen::Vector2d& c) {
  return std::atan2(-(p.y() - c.y()), p.x() - c.x());
}

bool on_screen_depth(const Eigen::Vector3d& s) { return s.z() > 0 && s.z() < 1; }

const Eigen::Vector3f kAxisColors[3] = {{0.95f, 0.25f, 0.25f}, {0.3f, 0.9f, 0.3f}, {0.3f, 0.5f, 1.0f}};
const Eigen::Vector3f kScaleColor{0.9f, 0.9f, 0.9f};
const Eigen::Vector3f kHighlight{1.0f, 0.9f, 0.2f};

}  // namespace

const char* to_string(GizmoPart p) {
  switch (p) {
    case GizmoPart::None:
      return "none";
    case GizmoPart::TranslateX:
      return "translate x";
    case GizmoPart::TranslateY:
      return "translate y";
    case GizmoPart::TranslateZ:
      return "translate z";
    case GizmoPart::RotateX:
      return "rotate x";
    case GizmoPart::RotateY:
      return "rotate y";
    case GizmoPart::RotateZ:
      return "rotate z";
    case GizmoPart::Scale:
      return "scale";
  }
  return "?";
}

int gizmo_axis(GizmoPart p) {
  switch (p) {
    case GizmoPart::TranslateX:
    case GizmoPart::RotateX:
      return 0;
    case GizmoPart::TranslateY:
    case GizmoPart::RotateY:
      return 1;
    case GizmoPart::TranslateZ:
    case GizmoPart::RotateZ:
      return 2;
    default:
      return -1;
  }
}

std::optional<double> closest_axis_parameter(const geometry::Ray& ray, const Eigen::Vector3d& center,
                                             const Eigen::Vector3d& axis) {
  // Closest points of two lines: minimise |c + t a - (o + s d)|² over t and s.
  const Eigen::Vector3d w = center - ray.origin;
  const double b = axis.dot(ray.direction), d = axis.dot(w), e = ray.direction.dot(w);
  const double denom = 1 - b * b;  // both unit: 1 - cos²
  if (denom < 1e-9) return std::nullopt;
  return (b * e - d) / denom;
}

double distance_to_segment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

Eigen::Matrix4d translation(const Eigen::Vector3d& offset) {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topRightCorner<3, 1>() = offset;
  return T;
}

Eigen::Matrix4d rotation_about(const Eigen::Vector3d& center, const Eigen::Vector3d& axis, double angle) {
  Eigen::Matrix4d R = Eigen::Matrix4d::Identity();
  R.topLeftCorner<3, 3>() = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  return translation(center) * R * translation(-center);
}

Eigen::Matrix4d scale_about(const Eigen::Vector3d& center, double factor) {
  Eigen::Matrix4d S = Eigen::Matrix4d::Identity();
  S.topLeftCorner<3, 3>() *= factor;
  return translation(center) * S * translation(-center);
}

Gizmo::Gizmo(GizmoOptions options) : options_(options) {}

void Gizmo::set_center(const Eigen::Vector3d& center) { center_ = center; }

double Gizmo::world_size(const CameraMatrices& camera) const { return world_size_at(camera, center_); }

double Gizmo::world_size_at(const CameraMatrices& camera, const Eigen::Vector3d& point) const {
  const Eigen::Vector3d s = geometry::project(camera, point);
  const double depth = std::clamp(s.z(), 0.0, 1.0);
  const Eigen::Vector3d a = geometry::unproject(camera, s.x(), s.y(), depth);
  const Eigen::Vector3d b = geometry::unproject(camera, s.x() + options_.size_px, s.y(), depth);
  return (b - a).norm();
}

std::vector<Gizmo::Polyline> Gizmo::parts(const CameraMatrices& camera) const {
  const double L = world_size(camera);
  const Eigen::Vector3d eye = geometry::eye_position(camera);
  std::vector<Polyline> out;
  const GizmoPart translate[3] = {GizmoPart::TranslateX, GizmoPart::TranslateY, GizmoPart::TranslateZ};
  const GizmoPart rotate[3] = {GizmoPart::RotateX, GizmoPart::RotateY, GizmoPart::RotateZ};
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3d axis = unit_axis(a), tip = center_ + L * axis;
    out.push_back({translate[a], {center_ + options_.shaft_start * L * axis, tip}, false});
    // Arrowhead in the plane facing the eye.
    const Eigen::Vector3d side = axis.cross(eye - tip);
    if (side.norm() > 1e-12) {
      const Eigen::Vector3d p = side.normalized();
      out.push_back(
          {translate[a], {tip - 0.14 * L * axis + 0.06 * L * p, tip, tip - 0.14 * L * axis - 0.06 * L * p}, false});
    }
    const Eigen::Vector3d u = unit_axis((a + 1) % 3), v = unit_axis((a + 2) % 3);
    Polyline ring{rotate[a], {}, true};
    const double r = options_.ring_fraction * L;
    for (int k = 0; k < options_.ring_segments; ++k) {
      const double t = 2 * std::numbers::pi * k / options_.ring_segments;
      ring.points.push_back(center_ + r * (std::cos(t) * u + std::sin(t) * v));
    }
    out.push_back(std::move(ring));
  }
  // The scale square faces the camera: its sides follow the view's right and up vectors.
  const Eigen::Vector3d right = camera.view.block<1, 3>(0, 0).transpose(),
                        up = camera.view.block<1, 3>(1, 0).transpose();
  const double h = options_.square_fraction * L;
  out.push_back({GizmoPart::Scale,
                 {center_ + h * (right + up), center_ + h * (-right + up), center_ + h * (-right - up),
                  center_ + h * (right - up)},
                 true});
  return out;
}

GizmoPart Gizmo::hit(const CameraMatrices& camera, const Eigen::Vector2d& pixel) const {
  GizmoPart best = GizmoPart::None;
  double best_d = options_.pick_tolerance_px;
  for (const Polyline& line : parts(camera)) {
    std::vector<Eigen::Vector3d> s;
    for (const auto& p : line.points) s.push_back(geometry::project(camera, p));
    const size_t n = s.size(), segments = line.closed ? n : n - 1;
    for (size_t k = 0; k < segments; ++k) {
      const Eigen::Vector3d &a = s[k], &b = s[(k + 1) % n];
      if (!on_screen_depth(a) || !on_screen_depth(b)) continue;
      const double d = distance_to_segment(pixel, a.head<2>(), b.head<2>());
      if (d < best_d) best_d = d, best = line.part;
    }
    if (line.part == GizmoPart::Scale && on_screen_depth(s[0])) {
      // Inside the square counts as on it: the whole square is the handle.
      Eigen::Vector2d lo = s[0].head<2>(), hi = lo;
      for (const auto& q : s) lo = lo.cwiseMin(q.head<2>()), hi = hi.cwiseMax(q.head<2>());
      if ((pixel.array() >= lo.array()).all() && (pixel.array() <= hi.array()).all()) return GizmoPart::Scale;
    }
  }
  return best;
}

bool Gizmo::begin_drag(const CameraMatrices& camera, const Eigen::Vector2d& pixel) {
  const GizmoPart part = hit(camera, pixel);
  if (part == GizmoPart::None) return false;
  const int a = gizmo_axis(part);
  if (part >= GizmoPart::TranslateX && part <= GizmoPart::TranslateZ) {
    const auto t = closest_axis_parameter(geometry::unproject_ray(camera, pixel.x(), pixel.y()), center_, unit_axis(a));
    if (!t) return false;  // looking straight down the axis: no direction to drag along
    start_parameter_ = *t;
  }
  active_ = part;
  anchor_ = center_;
  drag_camera_ = camera;
  start_pixel_ = pixel;
  const Eigen::Vector2d c = geometry::project(camera, center_).head<2>();
  last_angle_ = screen_angle(pixel, c);
  turned_ = 0;
  return true;
}

Eigen::Matrix4d Gizmo::drag_to(const Eigen::Vector2d& pixel) {
  if (!dragging()) return Eigen::Matrix4d::Identity();
  const int a = gizmo_axis(active_);
  const Eigen::Vector3d& o = anchor_;
  const Eigen::Vector2d c = geometry::project(drag_camera_, o).head<2>();
  switch (active_) {
    case GizmoPart::TranslateX:
    case GizmoPart::TranslateY:
    case GizmoPart::TranslateZ: {
      const auto t =
          closest_axis_parameter(geometry::unproject_ray(drag_camera_, pixel.x(), pixel.y()), o, unit_axis(a));
      // Near the horizon of a steep axis the closest point runs off to infinity: cap a
      // single drag at a hundred gizmo lengths.
      const double limit = 100 * world_size_at(drag_camera_, o);
      const double d = t ? std::clamp(*t - start_parameter_, -limit, limit) : 0.0;
      return translation(d * unit_axis(a));
    }
    case GizmoPart::RotateX:
    case GizmoPart::RotateY:
    case GizmoPart::RotateZ: {
      // The angle the cursor swept around the gizmo's centre on screen, unwrapped so a drag
      // can turn past half a turn; its sign follows whether the axis points at the viewer.
      const double angle = screen_angle(pixel, c);
      double step = angle - last_angle_;
      while (step > std::numbers::pi) step -= 2 * std::numbers::pi;
      while (step < -std::numbers::pi) step += 2 * std::numbers::pi;
      if ((pixel - c).norm() > 2) turned_ += step, last_angle_ = angle;  // at the centre the angle is noise
      const Eigen::Vector3d axis = unit_axis(a);
      const double facing = axis.dot(geometry::eye_position(drag_camera_) - o);
      return rotation_about(o, axis, facing >= 0 ? turned_ : -turned_);
    }
    case GizmoPart::Scale: {
      // Travel outwards from the grab point, along centre → grab point on screen (up and to
      // the right when the square was grabbed at its centre): the same travel scales as much
      // wherever the square was grabbed, and no grab near the centre makes a drag jump.
      const Eigen::Vector2d out = start_pixel_ - c;
      const Eigen::Vector2d dir =
          out.norm() > 2 ? Eigen::Vector2d(out.normalized()) : Eigen::Vector2d(1, -1).normalized();
      const double travel = (pixel - start_pixel_).dot(dir);
      return scale_about(o, std::exp(std::clamp(travel / options_.size_px, -4.0, 4.0)));
    }
    case GizmoPart::None:
      break;
  }
  return Eigen::Matrix4d::Identity();
}

void Gizmo::end_drag() { active_ = GizmoPart::None; }

void Gizmo::draw(const CameraMatrices& camera, LineItem& item) const {
  item.clear();
  for (const Polyline& line : parts(camera)) {
    const int a = gizmo_axis(line.part);
    const bool lit = line.part == active_ || (active_ == GizmoPart::None && line.part == hovered);
    const Eigen::Vector3f color = lit ? kHighlight : a < 0 ? kScaleColor : kAxisColors[a];
    std::vector<Eigen::Vector3d> pts = line.points;
    if (line.closed) pts.push_back(pts.front());
    item.add_strip(pts, color);
  }
  item.width = 3.0f;
  item.on_top = true;
}

}  // namespace lapis::viewer
