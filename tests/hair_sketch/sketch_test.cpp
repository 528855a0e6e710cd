// Sketch interpretation (thesis §4.5, Fig. 4.3) with synthetic strokes: screen points from
// projecting known 3D paths with a known camera.
#include <doctest/doctest.h>

#include <cmath>

#include "lapis/core/error.h"
#include "sketch_fixture.h"

using namespace hair_test;
using lapis::geometry::CameraMatrices;

namespace {

SketchOptions options() {
  SketchOptions o;
  o.spacing = 0.05;
  return o;
}

// A path on the scalp over the right side of the head, from near the top to the back.
std::vector<Eigen::Vector3d> scalp_path() {
  std::vector<Eigen::Vector3d> p;
  for (int i = 0; i <= 30; ++i) {
    const double a = 0.3 + 0.7 * i / 30;
    p.push_back(on_head({0.45, std::cos(a), -std::sin(a)}));
  }
  return p;
}

CameraMatrices side_camera() { return look_at({5, 1.5, -0.5}, {0, 0.4, -0.3}); }

double arc_length(const std::vector<Eigen::Vector3d>& p) {
  double l = 0;
  for (size_t i = 1; i < p.size(); ++i) l += (p[i] - p[i - 1]).norm();
  return l;
}

// A straight curve down the y axis, seen from +z: its strip faces the camera.
std::vector<Eigen::Vector3d> straight_curve() {
  std::vector<Eigen::Vector3d> c;
  for (int i = 0; i <= 20; ++i) c.emplace_back(0, -0.05 * i, 0);
  return c;
}

const Eigen::Vector3d kFrontEye(0, -0.5, 5);
CameraMatrices front_camera() { return look_at(kFrontEye, {0, -0.5, 0}); }

Stroke screen(const CameraMatrices& c, std::vector<Eigen::Vector3d> pts) { return project_path(c, pts); }

// Points from a to b (3D, in the plane z = 0), n steps.
std::vector<Eigen::Vector3d> line(Eigen::Vector3d a, Eigen::Vector3d b, int n = 12) {
  std::vector<Eigen::Vector3d> p;
  for (int i = 0; i <= n; ++i) p.push_back(a + (b - a) * (double(i) / n));
  return p;
}

}  // namespace

TEST_CASE("hair_sketch: a stroke from the scalp creates a stream curve on or above it along the path") {
  const Head& head = bundled_head();
  const auto path = scalp_path();
  const CameraMatrices cam = side_camera();
  Stroke stroke = project_path(cam, path);
  // Continue the stroke past the scalp: those points take the last scalp point's depth.
  const Eigen::Vector2d step = stroke.back() - stroke[stroke.size() - 2];
  for (int k = 1; k <= 15; ++k) stroke.push_back(stroke.back() + step);
  const SketchOptions o = options();
  const StreamCurve c = stream_curve_from_stroke(stroke, cam, head, o);
  REQUIRE(c.points.size() > 10);
  CHECK(c.tail_segments == o.tail_segments);
  for (const auto& p : c.points) {
    CHECK_FALSE(head.inside(p));
    const auto [n, foot] = head.closest(p);
    // Lifted points are resampled along chords: a curved stretch may dip a little.
    CHECK((p - foot).dot(n) >= 0.5 * o.lift * o.spacing);
  }
  // Resampled at d.
  for (size_t i = 1; i + 1 < c.points.size(); ++i) {  // arc length d apart, so chords a bit less
    CHECK((c.points[i] - c.points[i - 1]).norm() <= o.spacing + 1e-9);
    CHECK((c.points[i] - c.points[i - 1]).norm() >= 0.85 * o.spacing);
  }
  // Follows the path: the part as long as the path stays within half a spacing of it, and
  // every path point has the curve nearby.
  double run = 0;
  for (size_t i = 0; i < c.points.size() && run < arc_length(path) - o.spacing; ++i) {
    CHECK(distance_to_path(c.points[i], path) < 0.5 * o.spacing);
    if (i + 1 < c.points.size()) run += (c.points[i + 1] - c.points[i]).norm();
  }
  for (const auto& q : path) CHECK(distance_to_path(q, c.points) < o.spacing);
  CHECK(arc_length(c.points) > arc_length(path) + 3 * o.spacing);  // the off-scalp part
}

TEST_CASE("hair_sketch: unusable strokes are rejected with their reason") {
  const Head& head = bundled_head();
  const CameraMatrices cam = side_camera();
  const SketchOptions o = options();
  const Stroke on_scalp = project_path(cam, scalp_path());
  CHECK_THROWS_WITH_AS(stream_curve_from_stroke({{5, 5}, {20, 20}}, cam, head, o),
                       "hair_sketch::stream_curve_from_stroke(): stroke misses the head", StrokeRejected);
  CHECK_THROWS_WITH_AS(stream_curve_from_stroke({on_scalp[0]}, cam, head, o),
                       doctest::Contains("stroke has 1 points, expected at least 2"), StrokeRejected);
  CHECK_THROWS_WITH_AS(stream_curve_from_stroke({on_scalp[0], on_scalp[0], on_scalp[0]}, cam, head, o),
                       doctest::Contains("degenerate stroke"), StrokeRejected);
  CHECK_THROWS_WITH_AS(stream_curve_from_stroke({on_scalp[0], {NAN, 3}}, cam, head, o), doctest::Contains("not finite"),
                       StrokeRejected);
  // Starting on the face (head, not scalp).
  const Stroke face{{400, 300}, {400, 360}};  // the face's middle, seen from the front
  CHECK_THROWS_WITH_AS(stream_curve_from_stroke(face, look_at({0, 0, 5}, {0, 0, 0}), head, o),
                       doctest::Contains("does not start on the scalp"), StrokeRejected);
  // A dividing curve must stay on the scalp.
  Stroke off = on_scalp;
  off.push_back({5, 5});
  CHECK_THROWS_WITH_AS(dividing_curve_from_stroke(off, cam, head, o), doctest::Contains("misses the head"),
                       StrokeRejected);
  const DividingCurve d = dividing_curve_from_stroke(on_scalp, cam, head, o);
  for (const auto& p : d.points) CHECK(distance_to_path(p, scalp_path()) < 0.5 * o.spacing);
}

TEST_CASE("hair_sketch: supporting surfaces follow Fig. 4.3 (a) ruled through the viewpoint, (b) strip") {
  const auto c = straight_curve();
  const SketchOptions o = options();
  const auto ruled = make_supporting_surface(c, kFrontEye, SupportMode::Ruled, o);
  for (size_t i = 0; i < c.size(); ++i)  // rulings point from the viewpoint through the curve
    CHECK(ruled.rulings[i].dot((c[i] - kFrontEye).normalized()) == doctest::Approx(1.0));
  const auto strip = make_supporting_surface(c, kFrontEye, SupportMode::Strip, o);
  for (size_t i = 0; i + 1 < c.size(); ++i) {  // orthogonal to the segment–viewpoint triangle
    CHECK(std::abs(strip.rulings[i].dot(c[i + 1] - c[i])) < 1e-12);
    CHECK(std::abs(strip.rulings[i].dot(kFrontEye - c[i])) < 1e-9);
  }
  // Seen from its own viewpoint the ruled surface is edge-on: no usable hit.
  const auto ray = lapis::geometry::unproject_ray(front_camera(), 420, 300);
  const auto hit = ruled.intersect(ray);
  CHECK((!hit || !hit->on));
  const auto shit = strip.intersect(lapis::geometry::unproject_ray(front_camera(), 410, 320));
  REQUIRE(shit);
  CHECK(shit->on);
  CHECK(std::abs(shit->point.z()) < 1e-9);
}

TEST_CASE("hair_sketch: hint strokes are classified as in Fig. 4.3") {
  const auto c = straight_curve();  // length 1, d = 0.05, near = 0.075, width = 0.3
  const SketchOptions o = options();
  const auto hint = [&](const std::vector<Eigen::Vector3d>& pts, SupportMode m = SupportMode::Strip,
                        const CameraMatrices& camera = front_camera()) {
    return interpret_hint(c, kFrontEye, m, screen(camera, pts), camera, o);
  };
  SUBCASE("insert (g, h): starts and ends near the curve") {
    std::vector<Eigen::Vector3d> bulge;
    for (int i = 0; i <= 16; ++i) {
      const double t = i / 16.0;
      bulge.emplace_back(0.02 + 0.2 * std::sin(M_PI * t), -0.3 - 0.4 * t, 0);
    }
    const HintEdit e = hint(bulge);
    CHECK(e.kind == HintKind::Insert);
    CHECK(e.points.front().isApprox(c.front()));
    CHECK(e.points.back().y() == doctest::Approx(-1.0).epsilon(0.02));
    double max_x = 0;
    for (const auto& p : e.points) {
      max_x = std::max(max_x, p.x());
      CHECK(std::abs(p.z()) < 1e-6);
    }
    CHECK(max_x == doctest::Approx(0.22).epsilon(0.1));
    // Drawn backwards, it is the same insertion.
    std::reverse(bulge.begin(), bulge.end());
    CHECK(hint(bulge).kind == HintKind::Insert);
  }
  SUBCASE("concatenate (e, f): starts near, ends far, off the surface") {
    const HintEdit e = hint(line({0.01, -0.5, 0}, {0.8, -0.9, 0}, 20));
    CHECK(e.kind == HintKind::Concatenate);
    // The curve runs to the stroke's start, then along the stroke, past the surface's
    // width (depth extrapolated) to its end.
    CHECK(e.points.back().x() > 0.6);
    CHECK(std::abs(e.points.back().z()) < 0.05);
    for (const auto& p : e.points)
      if (p.x() < 1e-9) CHECK(p.y() >= -0.5 - 1e-6);
  }
  SUBCASE("cut (c, d): starts away from the curve and runs across it") {
    const HintEdit e = hint(line({-0.2, -0.35, 0}, {0.2, -0.45, 0}));
    CHECK(e.kind == HintKind::Cut);
    CHECK(arc_length(e.points) == doctest::Approx(0.4).epsilon(0.03));
    // The same cut drawn on the ruled surface from another viewpoint (the curve's plane x = 0
    // seen from +x).
    const CameraMatrices side = look_at({5, -0.5, 0}, {0, -0.5, 0});
    const HintEdit r = hint(line({0, -0.35, -0.2}, {0, -0.45, 0.2}), SupportMode::Ruled, side);
    CHECK(r.kind == HintKind::Cut);
    CHECK(arc_length(r.points) == doctest::Approx(0.4).epsilon(0.03));
  }
  SUBCASE("rejected: off the surface, or matching no rule") {
    CHECK_THROWS_WITH_AS(hint(line({0.9, -0.3, 0}, {0.9, -0.6, 0})),
                         doctest::Contains("does not start on the curve's supporting surface"), StrokeRejected);
    CHECK_THROWS_WITH_AS(hint(line({0.2, -0.3, 0}, {0.25, -0.6, 0})), doctest::Contains("does not run across it"),
                         StrokeRejected);
    CHECK_THROWS_WITH_AS(hint(line({0.2, -0.02, 0}, {-0.2, -0.02, 0}, 2)),
                         doctest::Contains("shorter than one grid spacing"), StrokeRejected);
  }
}

TEST_CASE("hair_sketch: a tilt stroke beside a dividing curve sets alpha at its end, on its side") {
  const Head& head = bundled_head();
  const SketchOptions o = options();
  const CameraMatrices top = look_at({0, 5, 0}, {0, 0, 0}, {0, 0, -1});
  // A parting from the front hairline over the top to the back, on the midline.
  std::vector<Eigen::Vector3d> path;
  for (int i = 0; i <= 20; ++i) {
    const double a = -0.6 + 1.2 * i / 20;
    path.push_back(on_head({0, std::cos(a), std::sin(a)}));
  }
  const DividingCurve curve = dividing_curve_from_stroke(project_path(top, path), top, head, o);
  const auto tilt_stroke = [&](double s, int side, double alpha) {
    const Eigen::Vector3d foot = curve.points[std::lround(s * (curve.points.size() - 1))];
    const Eigen::Vector3d x0 = dividing_side_axis(curve, head, s);
    const Eigen::Vector3d y = head.closest(foot).first;
    const Eigen::Vector3d dir = Eigen::AngleAxisd(alpha, y) * (side * x0);
    std::vector<Eigen::Vector3d> pts;
    for (int k = 1; k <= 8; ++k) pts.push_back(on_head(foot + 0.04 * k * dir - head.center));
    return project_path(top, pts);
  };
  const TiltEdit a = interpret_tilt(curve, tilt_stroke(0.15, +1, 0.4), top, head, o);
  CHECK(a.side == 1);
  CHECK(a.end == 0);
  CHECK(a.curve.alpha0 == doctest::Approx(0.4).epsilon(0.25));
  CHECK(a.curve.alpha1 == 0.0);
  const TiltEdit b = interpret_tilt(a.curve, tilt_stroke(0.85, -1, -0.3), top, head, o);
  CHECK(b.side == -1);
  CHECK(b.end == 1);
  CHECK(b.curve.alpha0 == a.curve.alpha0);
  CHECK(b.curve.alpha1 == doctest::Approx(-0.3).epsilon(0.25));
  // Mirrored side, same drawn angle: the opposite sign would be wrong.
  const TiltEdit m = interpret_tilt(curve, tilt_stroke(0.15, -1, 0.4), top, head, o);
  CHECK(m.side == -1);
  CHECK(m.curve.alpha0 == doctest::Approx(0.4).epsilon(0.25));
  CHECK_THROWS_WITH_AS(
      interpret_tilt(curve, project_path(top, {on_head({1, 0.2, 0}), on_head({1, 0, 0.2})}), top, head, o),
      doctest::Contains("from the parting"), StrokeRejected);
}

namespace {

// A ponytail's four curves as drawn from behind: the spine from the crown down the back of the
// head and off it, a flat loop of radius r around it (its C1), and profiles narrowing along it.
struct BackPonytail {
  std::vector<Eigen::Vector3d> spine, loop, pa, pb;
  double r = 0.12;
  BackPonytail() {
    for (int i = 0; i <= 10; ++i) spine.push_back(on_head({0, std::cos(0.9 + 0.05 * i), -std::sin(0.9 + 0.05 * i)}));
    const Eigen::Vector3d start = spine.back(), down(0, -1, -0.15);
    for (int i = 1; i <= 12; ++i) spine.push_back(start + 0.08 * i * down.normalized() + Eigen::Vector3d(0, 0, -0.1));
    for (int k = 0; k <= 24; ++k) {
      const double phi = 2 * M_PI * k / 24;
      loop.push_back(spine[13] + r * Eigen::Vector3d(std::cos(phi), 0.3 * std::sin(phi), 0));
    }
    for (int i = 12; i <= 22; ++i) {
      const double ri = r * (1.0 - 0.05 * (i - 12));
      pa.push_back(spine[i] + Eigen::Vector3d(ri, 0, 0));
      pb.push_back(spine[i] - Eigen::Vector3d(ri, 0, 0));
    }
  }
};

}  // namespace

TEST_CASE("hair_sketch: four strokes make a ponytail whose cross sections lie between the profiles") {
  const Head& head = bundled_head();
  const SketchOptions o = options();
  const CameraMatrices back = look_at({0, 0.3, -5}, {0, 0.0, -0.8});
  const BackPonytail drawn;
  const auto& [spine, loop, pa, pb, r] = drawn;
  const Eigen::Vector3d c1 = spine[13];
  const Ponytail t = ponytail_from_strokes(
      {project_path(back, spine), project_path(back, loop), project_path(back, pa), project_path(back, pb)}, back, head,
      o);
  const Ponytail::Section s = t.first_section();
  CHECK(s.radius > 0.5 * r);  // a planar loop drawn on the strip: mean distance 2r/π .. r
  CHECK(s.radius < 1.1 * r);
  // Off the scalp the spine takes the last scalp depth, so compare where it is drawn.
  CHECK((lapis::geometry::project(back, s.center) - lapis::geometry::project(back, c1)).head<2>().norm() < 12);
  // Profiles on opposite sides of the spine, and the section's circle between them.
  const Eigen::Vector3d side_a = t.profile_a.front() - s.center, side_b = t.profile_b.front() - s.center;
  CHECK(side_a.dot(side_b) < 0);
  for (size_t i = 0; i < t.profile_a.size(); ++i) {
    const double da = distance_to_path(t.profile_a[i], t.spine), db = distance_to_path(t.profile_b[i], t.spine);
    CHECK(std::abs(da - db) < o.spacing);
  }
  CHECK(s.radius <= distance_to_path(t.profile_a.front(), t.spine) + o.spacing);
  CHECK(s.radius >= distance_to_path(t.profile_a.back(), t.spine) - o.spacing);
  // A missing cross section is a reason, not a crash.
  CHECK_THROWS_WITH_AS(
      ponytail_from_strokes({project_path(back, spine), Stroke{{1, 1}}, project_path(back, pa), project_path(back, pb)},
                            back, head, o),
      doctest::Contains("cross section"), StrokeRejected);
}

TEST_CASE("hair_sketch: a ponytail's strokes are each read with the camera they were drawn with") {
  const Head& head = bundled_head();
  const SketchOptions o = options();
  const CameraMatrices back = look_at({0, 0.3, -5}, {0, 0.0, -0.8});
  // The view turned 35 degrees between the spine and the other strokes.
  const CameraMatrices turned = look_at({-5 * std::sin(0.6), 0.8, -5 * std::cos(0.6)}, {0, 0.0, -0.8});
  std::vector<Eigen::Vector3d> spine;
  for (int i = 0; i <= 10; ++i) spine.push_back(on_head({0, std::cos(0.9 + 0.05 * i), -std::sin(0.9 + 0.05 * i)}));
  const Eigen::Vector3d start = spine.back(), down(0, -1, -0.15);
  for (int i = 1; i <= 12; ++i) spine.push_back(start + 0.08 * i * down.normalized() + Eigen::Vector3d(0, 0, -0.1));
  // The spine as read, and 3D curves on its supporting surface (seen from `back`).
  const Stroke spine_stroke = project_path(back, spine);
  const std::vector<Eigen::Vector3d> read = stream_curve_from_stroke(spine_stroke, back, head, o).points;
  const SupportingSurface surf =
      make_supporting_surface(read, lapis::geometry::eye_position(back), SupportMode::Strip, o);
  // Points on segment i's piece of the surface at offset w (its midpoint, its mean ruling).
  const auto on_surface = [&](int i, double w) {
    return Eigen::Vector3d(0.5 * (surf.points[i] + surf.points[i + 1]) +
                           w * (surf.rulings[i] + surf.rulings[i + 1]).normalized());
  };
  const int at = static_cast<int>(0.6 * read.size());
  const double r = 0.12;
  std::vector<Eigen::Vector3d> loop, pa, pb;
  for (int k = 0; k <= 24; ++k) {
    const double phi = 2 * M_PI * k / 24;
    const int i =
        std::clamp(at + static_cast<int>(std::lround(1.5 * std::sin(phi))), 0, static_cast<int>(read.size()) - 2);
    loop.push_back(on_surface(i, r * std::cos(phi)));  // across the spine, on the strip
  }
  for (int i = at; i + 1 < static_cast<int>(read.size()); ++i) {
    pa.push_back(on_surface(i, r));
    pb.push_back(on_surface(i, -r));
  }
  const std::array<Stroke, 4> strokes{spine_stroke, project_path(turned, loop), project_path(turned, pa),
                                      project_path(turned, pb)};
  const Ponytail each = ponytail_from_strokes(strokes, {back, turned, turned, turned}, head, o);
  // Each camera's reading recovers the curves drawn on the surface.
  for (const auto& q : each.cross_section) CHECK(distance_to_path(q, loop) < 0.25 * o.spacing);
  for (const auto& q : each.profile_a) CHECK(distance_to_path(q, pa) < 0.25 * o.spacing);
  // Read with one camera for all four (the last one), the same strokes land elsewhere.
  const Ponytail last = ponytail_from_strokes(strokes, turned, head, o);
  double off = 0;
  for (const auto& q : last.cross_section) off = std::max(off, distance_to_path(q, loop));
  CHECK(off > 2 * o.spacing);
  // Through the document: a recorded stroke with four cameras makes the same ponytail.
  Hairstyle style;
  style.settings = small_settings();
  const Grid grid = hairstyle_grid(head, style.settings);
  RecordedStroke rec = recorded(StrokeAction::Ponytail, turned, {strokes.begin(), strokes.end()});
  rec.cameras = {back, turned, turned, turned};
  Document doc(style);
  apply_stroke(doc, rec, head, grid);
  const auto& made = std::get<Ponytail>(doc.style().primitives.at(0).shape);
  const Ponytail expected =
      ponytail_from_strokes(strokes, {back, turned, turned, turned}, head, sketch_options(grid, style.settings));
  CHECK(made.cross_section == expected.cross_section);
  CHECK(doc.style().primitives[0].viewpoint == lapis::geometry::eye_position(back));
}

TEST_CASE("hair_sketch: a ponytail sketched from behind on a new style makes a tail, also narrower than a cell") {
  // Drawn alone, from behind; the loop reads as a section of radius 0.08, under half of the 25K
  // grid's spacing. With the gravity prior of a new style in the app (0.3), the hair above C1
  // falls to it; without it (the thesis' field) nothing says where that hair goes, and most of
  // it rises above the crown (docs/hair_sketch.md).
  const Head& head = bundled_head();
  const CameraMatrices back = look_at({0, 0.3, -5}, {0, 0.0, -0.8});
  const BackPonytail drawn;
  const auto& [spine, loop, pa, pb, r] = drawn;
  Hairstyle style;
  style.settings.grid.target_unknowns = 25000;
  style.settings.roots.count = 2000;
  style.settings.gravity_prior.strength = 0.3;
  const Grid grid = hairstyle_grid(head, style.settings);
  Document doc(style);
  apply_stroke(
      doc,
      recorded(StrokeAction::Ponytail, back,
               {project_path(back, spine), project_path(back, loop), project_path(back, pa), project_path(back, pb)}),
      head, grid);
  const auto& tail = std::get<Ponytail>(doc.style().primitives.at(0).shape);
  REQUIRE(tail.first_section().radius < 0.5 * grid.spacing);
  const HairstyleResult res = build_hairstyle(doc.style(), head);
  int rising = 0;  // strands reaching a tenth of the head's height above its top
  for (int s = 0; s < res.strands.count(); ++s)
    for (int i = res.strands.offsets[s]; i < res.strands.offsets[s + 1]; ++i)
      if (res.strands.points[i].y() > head.box.max().y() + 0.1 * head.box.sizes().y()) {
        ++rising;
        break;
      }
  const auto [entered, through] = strands_entering_tail(res.strands, tail, res.grid.spacing);
  MESSAGE(rising << " strands rise above the head; " << through << " of " << entered
                 << " strands entering the tail pass through C1, of " << res.strands.count());
  CHECK(rising == 0);
  CHECK(through >= 0.9 * entered);
  CHECK(through >= res.strands.count() / 10);  // a tail, not a few strands
}
