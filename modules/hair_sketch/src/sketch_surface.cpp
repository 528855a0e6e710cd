// Strokes whose depth comes from a curve's supporting surface (thesis §4.5, Fig. 4.3):
// the surface itself, hint-stroke editing (cut / concatenate / insert) and the ponytail's
// cross-section and profile curves.
#include <algorithm>
#include <cmath>

#include "curve_sampling.h"
#include "lapis/hair_sketch/sketch.h"
#include "sketch_stroke.h"

namespace lapis::hair_sketch {

const char* to_string(SupportMode m) { return m == SupportMode::Ruled ? "ruled" : "strip"; }

const char* to_string(HintKind k) {
  switch (k) {
    case HintKind::Cut:
      return "cut";
    case HintKind::Concatenate:
      return "concatenate";
    case HintKind::Insert:
      return "insert";
  }
  return "?";
}

double SupportingSurface::length() const { return detail::polyline_length(points); }

SupportingSurface make_supporting_surface(const std::vector<Eigen::Vector3d>& curve, const Eigen::Vector3d& viewpoint,
                                          SupportMode mode, const SketchOptions& options) {
  constexpr const char* fn = "hair_sketch::make_supporting_surface()";
  if (curve.size() < 2)
    throw InvalidArgument(std::string(fn) + ": curve has " + std::to_string(curve.size()) +
                          " points, expected at least 2");
  SupportingSurface s;
  s.points = curve;
  s.half_width = options.surface_width * options.spacing;
  const size_t n = curve.size();
  if (mode == SupportMode::Ruled) {
    // Fig. 4.3(a): lines from the viewpoint through the curve.
    for (const auto& p : curve) {
      const Eigen::Vector3d r = p - viewpoint;
      if (!(r.norm() > 0)) throw InvalidArgument(std::string(fn) + ": the viewpoint lies on the curve");
      s.rulings.push_back(r.normalized());
    }
    return s;
  }
  // Fig. 4.3(b): per segment, the normal of the segment–viewpoint triangle; a vertex takes
  // the mean of its segments' normals (kept on one side so the strip does not twist).
  std::vector<Eigen::Vector3d> seg(n - 1);
  for (size_t i = 0; i + 1 < n; ++i) {
    const Eigen::Vector3d m = (curve[i + 1] - curve[i]).cross(viewpoint - curve[i]);
    if (!(m.norm() > 1e-300))
      throw InvalidArgument(std::string(fn) + ": segment " + std::to_string(i) +
                            " points at the viewpoint (strip undefined)");
    seg[i] = m.normalized();
    if (i && seg[i].dot(seg[i - 1]) < 0) seg[i] = -seg[i];
  }
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d a = seg[std::min(i, n - 2)], b = seg[i == 0 ? 0 : i - 1];
    s.rulings.push_back((a + b).normalized());
  }
  return s;
}

std::optional<SupportingSurface::Hit> SupportingSurface::intersect(const geometry::Ray& ray) const {
  std::optional<Hit> best_on, best_off;
  double run = 0;
  for (size_t i = 0; i + 1 < points.size(); ++i) {
    // Each segment's piece of the surface as the plane of the segment and its mean ruling.
    const Eigen::Vector3d p0 = points[i], e = points[i + 1] - p0;
    const Eigen::Vector3d r = (rulings[i] + rulings[i + 1]).normalized();
    const double elen = e.norm();
    const Eigen::Vector3d nrm = e.cross(r);
    const double denom = ray.direction.dot(nrm);
    if (std::abs(denom) > 1e-9 * nrm.norm()) {
      const double t = (p0 - ray.origin).dot(nrm) / denom;
      const Eigen::Vector3d x = ray.origin + t * ray.direction - p0;
      const double ee = e.dot(e), er = e.dot(r), rr = r.dot(r), xe = x.dot(e), xr = x.dot(r);
      const double det = ee * rr - er * er;
      const double a = (xe * rr - xr * er) / det, w = (ee * xr - er * xe) / det;
      if (t > 0 && a >= -1e-9 && a <= 1 + 1e-9) {
        Hit h{ray.origin + t * ray.direction, run + std::clamp(a, 0.0, 1.0) * elen, w, t, std::abs(w) <= half_width};
        auto& best = h.on ? best_on : best_off;
        if (!best || (h.on ? h.t < best->t : std::abs(h.w) < std::abs(best->w))) best = h;
      }
    }
    run += elen;
  }
  return best_on ? best_on : best_off;
}

namespace {

// Stroke points in 3D on the surface. A hint stroke must start on it, and its points off
// the surface take the ray depth extrapolated linearly in screen arc length from the last
// two on-surface points (Fig. 4.3(f)); curves drawn on the surface (ponytail) use the
// surface's extension and extrapolate only where a ray misses even that.
struct Lifted {
  std::vector<Eigen::Vector3d> p;
  std::vector<SupportingSurface::Hit> hit;  // hit[i].on false when extrapolated
};

Lifted lift_onto(const SupportingSurface& surf, const Stroke& stroke, const geometry::CameraMatrices& camera, bool hint,
                 const char* fn) {
  Lifted out;
  std::vector<double> arc(stroke.size(), 0.0);
  for (size_t i = 1; i < stroke.size(); ++i) arc[i] = arc[i - 1] + (stroke[i] - stroke[i - 1]).norm();
  int last = -1, prev = -1;  // last two on-surface indices
  for (size_t i = 0; i < stroke.size(); ++i) {
    const geometry::Ray ray = geometry::unproject_ray(camera, stroke[i].x(), stroke[i].y());
    auto h = surf.intersect(ray);
    if (i == 0 && hint && !(h && h->on)) detail::reject(fn, "stroke does not start on the curve's supporting surface");
    if (h && (h->on || !hint || last < 0)) {
      out.p.push_back(h->point);
      out.hit.push_back(*h);
      if (h->on || !hint) prev = last, last = static_cast<int>(i);
      continue;
    }
    if (last < 0) detail::reject(fn, "stroke point " + std::to_string(i) + " misses the supporting surface");
    double t = out.hit[last].t;
    if (prev >= 0 && arc[last] > arc[prev])
      t += (out.hit[last].t - out.hit[prev].t) / (arc[last] - arc[prev]) * (arc[i] - arc[last]);
    SupportingSurface::Hit x;
    x.point = ray.origin + t * ray.direction;
    x.t = t;
    x.on = false;
    x.s = out.hit[last].s;
    x.w = h ? h->w : 1e300;
    out.p.push_back(x.point);
    out.hit.push_back(x);
  }
  return out;
}

std::vector<Eigen::Vector3d> curve_until(const std::vector<Eigen::Vector3d>& c, double s) {
  std::vector<Eigen::Vector3d> out{c.front()};
  double run = 0;
  for (size_t i = 0; i + 1 < c.size(); ++i) {
    const double l = (c[i + 1] - c[i]).norm();
    if (run + l >= s) {
      if (l > 0 && s > run) out.push_back(c[i] + (s - run) / l * (c[i + 1] - c[i]));
      return out;
    }
    out.push_back(c[i + 1]);
    run += l;
  }
  return out;
}

std::vector<Eigen::Vector3d> curve_from(const std::vector<Eigen::Vector3d>& c, double s) {
  std::vector<Eigen::Vector3d> rev(c.rbegin(), c.rend());
  auto part = curve_until(rev, detail::polyline_length(c) - s);
  return {part.rbegin(), part.rend()};
}

void append(std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b) {
  for (const auto& p : b)
    if (a.empty() || (p - a.back()).norm() > 0) a.push_back(p);
}

}  // namespace

HintEdit interpret_hint(const std::vector<Eigen::Vector3d>& curve, const Eigen::Vector3d& viewpoint, SupportMode mode,
                        const Stroke& stroke, const geometry::CameraMatrices& camera, const SketchOptions& options) {
  constexpr const char* fn = "hair_sketch::interpret_hint()";
  detail::check_stroke(stroke, options, fn);
  const SupportingSurface surf = make_supporting_surface(curve, viewpoint, mode, options);
  const Lifted l = lift_onto(surf, stroke, camera, true, fn);
  const double near = options.near * options.spacing;
  const auto is_near = [&](const SupportingSurface::Hit& h) { return h.on && std::abs(h.w) <= near; };
  const auto& a = l.hit.front();
  const auto& b = l.hit.back();
  HintEdit edit;
  if (is_near(a) && is_near(b)) {
    // Fig. 4.3(g)(h): the stroke replaces the curve between its ends, in curve order.
    edit.kind = HintKind::Insert;
    std::vector<Eigen::Vector3d> mid = l.p;
    double s0 = a.s, s1 = b.s;
    if (s1 < s0) std::reverse(mid.begin(), mid.end()), std::swap(s0, s1);
    edit.points = curve_until(curve, s0);
    append(edit.points, mid);
    append(edit.points, curve_from(curve, s1));
  } else if (is_near(a)) {
    // Fig. 4.3(e)(f): the curve ends where the stroke starts and continues along it.
    edit.kind = HintKind::Concatenate;
    edit.points = curve_until(curve, a.s);
    append(edit.points, l.p);
  } else {
    // Fig. 4.3(c)(d): a stroke from beside the curve across it cuts the curve there.
    std::optional<double> cut;
    for (size_t i = 0; i + 1 < l.hit.size() && !cut; ++i) {
      const auto &h0 = l.hit[i], &h1 = l.hit[i + 1];
      if (h0.on && h1.on && (h0.w > 0) != (h1.w > 0)) cut = h0.s + (h1.s - h0.s) * h0.w / (h0.w - h1.w);
    }
    if (!cut || is_near(b))
      detail::reject(fn,
                     "hint stroke starts away from the curve and does not run across it "
                     "(cut), nor starts near it (concatenate, insert)");
    edit.kind = HintKind::Cut;
    edit.points = curve_until(curve, *cut);
  }
  if (detail::polyline_length(edit.points) < options.spacing)
    detail::reject(fn,
                   std::string("the ") + to_string(edit.kind) + " would leave a curve shorter than one grid spacing");
  edit.points = detail::resample(edit.points, options.spacing, fn);
  return edit;
}

Ponytail ponytail_from_strokes(const std::array<Stroke, 4>& strokes, const geometry::CameraMatrices& camera,
                               const Head& head, const SketchOptions& options) {
  return ponytail_from_strokes(strokes, {camera, camera, camera, camera}, head, options);
}

Ponytail ponytail_from_strokes(const std::array<Stroke, 4>& strokes,
                               const std::array<geometry::CameraMatrices, 4>& cameras, const Head& head,
                               const SketchOptions& options) {
  constexpr const char* fn = "hair_sketch::ponytail_from_strokes()";
  Ponytail tail;
  try {
    tail.spine = stream_curve_from_stroke(strokes[0], cameras[0], head, options).points;
  } catch (const StrokeRejected& e) {
    detail::reject(fn, std::string("spine: ") + e.what());
  }
  // The spine's surface is seen from where the spine was drawn; the other strokes are rays of
  // their own cameras onto it (§4.5: the user turns the view to draw them).
  const SupportingSurface surf =
      make_supporting_surface(tail.spine, geometry::eye_position(cameras[0]), SupportMode::Strip, options);
  const char* names[] = {"spine", "cross section", "profile a", "profile b"};
  std::vector<Eigen::Vector3d>* outs[] = {nullptr, &tail.cross_section, &tail.profile_a, &tail.profile_b};
  for (int k = 1; k < 4; ++k) {
    try {
      detail::check_stroke(strokes[k], options, fn);
      *outs[k] = lift_onto(surf, strokes[k], cameras[k], false, fn).p;
    } catch (const StrokeRejected& e) {
      detail::reject(fn, std::string(names[k]) + ": " + e.what());
    }
  }
  if (tail.cross_section.size() < 3) detail::reject(fn, "cross section: fewer than 3 points");
  try {
    tail.first_section();
  } catch (const InvalidArgument& e) {
    detail::reject(fn, std::string("degenerate strokes: ") + e.what());
  }
  return tail;
}

}  // namespace lapis::hair_sketch
