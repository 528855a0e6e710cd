// Strokes whose depth comes from the scalp (thesis §4.5): stream-curve and dividing-curve
// creation, and the tilt hint beside a dividing curve.
#include <cmath>

#include "curve_sampling.h"
#include "lapis/core/format.h"
#include "lapis/hair_sketch/sketch.h"
#include "sketch_stroke.h"

namespace lapis::hair_sketch {

namespace detail {

void check_stroke(const Stroke& stroke, const SketchOptions& options, const char* fn) {
  if (stroke.size() < 2) reject(fn, "stroke has " + std::to_string(stroke.size()) + " points, expected at least 2");
  double length = 0;
  for (size_t i = 0; i < stroke.size(); ++i) {
    if (!stroke[i].allFinite()) reject(fn, "stroke point " + std::to_string(i) + " is not finite");
    if (i) length += (stroke[i] - stroke[i - 1]).norm();
  }
  if (length < options.min_stroke_pixels)
    reject(fn, "degenerate stroke: " + format_number(length) + " pixels long, expected at least " +
                   format_number(options.min_stroke_pixels));
}

double polyline_length(const std::vector<Eigen::Vector3d>& p) {
  double l = 0;
  for (size_t i = 1; i < p.size(); ++i) l += (p[i] - p[i - 1]).norm();
  return l;
}

}  // namespace detail

namespace {

struct ScalpHit {
  bool head = false, scalp = false;
  Eigen::Vector3d point;
};

ScalpHit cast(const geometry::CameraMatrices& camera, const Head& head, const Eigen::Vector2d& q) {
  const geometry::Ray ray = geometry::unproject_ray(camera, q.x(), q.y());
  const auto hit = head.bvh->intersect(ray.origin, ray.direction);
  if (!hit) return {};
  return {true, head.scalp_face[hit->face] != 0, hit->point};
}

// Keeps p at least `lift` outside the head: a curve below the scalp would constrain nodes
// where no strand grows.
Eigen::Vector3d keep_above(const Head& head, const Eigen::Vector3d& p, double lift) {
  const auto [normal, foot] = head.closest(p);
  if (head.inside(p) || (p - foot).dot(normal) < lift) return foot + lift * normal;
  return p;
}

// Resampling at d can fail on a curve that collapsed to a point; that is the stroke's fault.
std::vector<Eigen::Vector3d> resample_curve(const std::vector<Eigen::Vector3d>& p, double d, const char* fn) {
  if (detail::polyline_length(p) < d)
    detail::reject(fn, "degenerate stroke: its 3D curve is shorter than one grid spacing");
  return detail::resample(p, d, fn);
}

}  // namespace

StreamCurve stream_curve_from_stroke(const Stroke& stroke, const geometry::CameraMatrices& camera, const Head& head,
                                     const SketchOptions& options) {
  constexpr const char* fn = "hair_sketch::stream_curve_from_stroke()";
  detail::check_stroke(stroke, options, fn);
  const ScalpHit first = cast(camera, head, stroke[0]);
  if (!first.head) detail::reject(fn, "stroke misses the head");
  if (!first.scalp) detail::reject(fn, "stroke does not start on the scalp");
  const double d = options.spacing;
  std::vector<Eigen::Vector3d> points;
  double depth = geometry::project(camera, first.point).z();
  for (const auto& q : stroke) {
    const ScalpHit h = cast(camera, head, q);
    Eigen::Vector3d p;
    if (h.scalp) {
      p = h.point;
      depth = geometry::project(camera, p).z();
    } else {
      p = geometry::unproject(camera, q.x(), q.y(), depth);  // depth of the last scalp point
    }
    points.push_back(keep_above(head, p, options.lift * d));
  }
  StreamCurve curve;
  curve.points = resample_curve(points, d, fn);
  // Resampled points lie on chords between lifted ones, and a chord across a bulge of the face
  // (a brow, a cheek) runs inside the head: those points are lifted again.
  for (auto& p : curve.points)
    if (head.inside(p)) p = keep_above(head, p, options.lift * d);
  curve.tail_segments = options.tail_segments;
  return curve;
}

DividingCurve dividing_curve_from_stroke(const Stroke& stroke, const geometry::CameraMatrices& camera, const Head& head,
                                         const SketchOptions& options) {
  constexpr const char* fn = "hair_sketch::dividing_curve_from_stroke()";
  detail::check_stroke(stroke, options, fn);
  std::vector<Eigen::Vector3d> points;
  for (size_t i = 0; i < stroke.size(); ++i) {
    const ScalpHit h = cast(camera, head, stroke[i]);
    if (!h.head) detail::reject(fn, "stroke point " + std::to_string(i) + " misses the head");
    if (!h.scalp) detail::reject(fn, "stroke point " + std::to_string(i) + " is off the scalp (a parting lies on it)");
    points.push_back(keep_above(head, h.point, options.lift * options.spacing));
  }
  DividingCurve curve;
  curve.points = resample_curve(points, options.spacing, fn);
  return curve;
}

TiltEdit interpret_tilt(const DividingCurve& curve, const Stroke& stroke, const geometry::CameraMatrices& camera,
                        const Head& head, const SketchOptions& options) {
  constexpr const char* fn = "hair_sketch::interpret_tilt()";
  detail::check_stroke(stroke, options, fn);
  if (curve.points.size() < 2) detail::reject(fn, "the dividing curve has fewer than 2 points");
  std::vector<Eigen::Vector3d> p;
  for (const auto& q : stroke) {
    const ScalpHit h = cast(camera, head, q);
    if (h.head) p.push_back(h.point);
  }
  if (p.size() < 2) detail::reject(fn, "stroke misses the head");
  // Where along the parting the stroke starts, and on which side.
  const Eigen::Vector3d start = p.front();
  double best = 1e300, s_best = 0, total = detail::polyline_length(curve.points), run = 0;
  Eigen::Vector3d foot = curve.points.front();
  for (size_t i = 0; i + 1 < curve.points.size(); ++i) {
    const Eigen::Vector3d a = curve.points[i], e = curve.points[i + 1] - a;
    const double t = std::clamp((start - a).dot(e) / std::max(e.squaredNorm(), 1e-300), 0.0, 1.0);
    const double dist = (a + t * e - start).norm();
    if (dist < best) best = dist, s_best = run + t * e.norm(), foot = a + t * e;
    run += e.norm();
  }
  const double reach = options.surface_width * options.spacing;
  if (best > reach)
    detail::reject(fn, "stroke starts " + format_number(best / options.spacing) +
                           " grid spacings from the parting, expected within " + format_number(options.surface_width));
  const double s = total > 0 ? s_best / total : 0.0;
  const int end = s < 0.5 ? 0 : 1;
  // The side axis and scalp normal of the untilted frame at s.
  DividingCurve flat = curve;
  flat.alpha0 = flat.alpha1 = 0;
  const Eigen::Vector3d x0 = dividing_side_axis(flat, head, s);
  const Eigen::Vector3d y = head.closest(foot).first;
  Eigen::Vector3d dir = p.back() - p.front();
  dir -= dir.dot(y) * y;
  if (dir.norm() < 1e-9 * std::max(1.0, reach)) detail::reject(fn, "degenerate stroke: no direction on the scalp");
  const int side = (p.back() - foot).dot(x0) >= 0 ? 1 : -1;
  const Eigen::Vector3d axis = side * x0;  // hair flows along ±x (Fig. 4.4 right)
  const double alpha = std::atan2(axis.cross(dir).dot(y), axis.dot(dir));
  TiltEdit edit{curve, end, side};
  (end == 0 ? edit.curve.alpha0 : edit.curve.alpha1) = alpha;
  return edit;
}

}  // namespace lapis::hair_sketch
