// Strand detail: each kind measured against its parameters on straight strands, and on hair
// grown on the bundled head (determinism, roots, the head).
#include <doctest/doctest.h>

#include <omp.h>

#include <cmath>
#include <numbers>

#include "fixture.h"
#include "lapis/hair_sketch/scalp_avoidance.h"
#include "lapis/hair_sketch/strand_detail.h"
#include "lapis/hair_sketch/stream_curve.h"

using namespace hair_test;

namespace {

// Strands straight along `direction` from roots spaced 0.1 apart along z, 0.05 per segment.
Strands straight_strands(int count, const Eigen::Vector3f& direction, float length = 2.f) {
  Strands s;
  for (int k = 0; k < count; ++k) {
    const Eigen::Vector3f root(0, 0, 0.1f * k);
    for (int i = 0; i <= static_cast<int>(std::lround(length / 0.05f)); ++i)
      s.points.push_back(root + 0.05f * i * direction);
    s.offsets.push_back(static_cast<int>(s.points.size()));
  }
  return s;
}

// No head: every root in region 0, the centre below the strands (outward = +y).
DetailContext free_context(int strands) {
  DetailContext c;
  c.root_vertex.assign(strands, 0);
  c.center = Eigen::Vector3f(0, -1, 0);
  return c;
}

std::vector<Eigen::Vector3f> strand(const Strands& s, int i) {
  return {s.points.begin() + s.offsets[i], s.points.begin() + s.offsets[i + 1]};
}

StrandDetail make(const decltype(StrandDetail::shape)& shape, std::uint32_t seed = 1) {
  StrandDetail d;
  d.shape = shape;
  d.seed = seed;
  return d;
}

StrandDetail curl(double frequency, double radius) {
  CurlDetail c;
  c.frequency = frequency;
  c.radius = radius;
  c.phase_jitter = 0;
  c.radius_jitter = 0;
  return make(c);
}

// Turns per unit length and mean radius of a helix about the x axis, past x0.
std::pair<double, double> helix_about_x(const std::vector<Eigen::Vector3f>& p, double x0) {
  double turns = 0, radius = 0, angle = 0;
  int n = 0;
  double first_x = 0, last_x = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p[i].x() < x0) continue;
    const double a = std::atan2(p[i].z(), p[i].y());
    if (n == 0)
      first_x = p[i].x();
    else {
      double da = a - angle;
      while (da > std::numbers::pi) da -= 2 * std::numbers::pi;
      while (da < -std::numbers::pi) da += 2 * std::numbers::pi;
      turns += da / (2 * std::numbers::pi);
    }
    angle = a;
    last_x = p[i].x();
    radius += std::hypot(p[i].y(), p[i].z());
    ++n;
  }
  return {std::abs(turns) / (last_x - first_x), radius / n};
}

}  // namespace

TEST_CASE("hair_sketch: a curl's measured frequency and radius are its parameters") {
  const Strands s = straight_strands(1, Eigen::Vector3f::UnitX());
  for (const double f : {2.0, 5.0, 11.0}) {
    for (const double r : {0.01, 0.04, 0.1}) {
      const Strands out = apply_strand_detail(s, {curl(f, r)}, free_context(1));
      const auto [turns, radius] = helix_about_x(strand(out, 0), 0.2);
      CAPTURE(f);
      CAPTURE(r);
      CHECK(turns == doctest::Approx(f).epsilon(0.05));
      CHECK(radius == doctest::Approx(r).epsilon(0.05));
      CHECK(strand(out, 0).front() == strand(s, 0).front());  // still at its root
    }
  }
}

TEST_CASE("hair_sketch: curl growth widens and tightens toward the tip; a wave stays in one plane") {
  const Strands s = straight_strands(1, Eigen::Vector3f::UnitX());
  StrandDetail d = curl(4, 0.03);
  std::get<CurlDetail>(d.shape).radius_growth = 1;     // r doubles at the tip
  std::get<CurlDetail>(d.shape).frequency_growth = 1;  // so does f
  const auto p = strand(apply_strand_detail(s, {d}, free_context(1)), 0);
  const auto tip = helix_about_x({p.end() - 40, p.end()}, 1.8);
  const auto middle = helix_about_x(p, 0.9);
  CHECK(tip.second == doctest::Approx(0.03 * 1.95).epsilon(0.05));
  CHECK(tip.first == doctest::Approx(4 * 1.95).epsilon(0.05));
  CHECK(middle.first < tip.first);

  std::get<CurlDetail>(d.shape).helical = false;
  CHECK(std::string(detail_type(d)) == "wave");
  const auto wave = strand(apply_strand_detail(s, {d}, free_context(1)), 0);
  double off_plane = 0, in_plane = 0;
  for (const auto& q : wave)
    off_plane = std::max(off_plane, std::abs(double(q.y()))), in_plane = std::max(in_plane, std::abs(double(q.z())));
  CHECK(off_plane < 1e-6);  // the normal starts outward (+y); the wave swings along z
  CHECK(in_plane == doctest::Approx(0.06).epsilon(0.05));
}

TEST_CASE("hair_sketch: curl jitter stays within its range and varies between strands") {
  const Strands s = straight_strands(200, Eigen::Vector3f::UnitX());
  StrandDetail d = curl(5, 0.04);
  std::get<CurlDetail>(d.shape).radius_jitter = 0.2;
  std::get<CurlDetail>(d.shape).phase_jitter = 1;
  const Strands out = apply_strand_detail(s, {d}, free_context(200));
  double lo = 1e9, hi = 0;
  std::vector<double> phases;
  for (int i = 0; i < out.count(); ++i) {
    auto p = strand(out, i);
    for (auto& q : p) q.z() -= 0.1f * i;  // about the strand's own axis
    const double r = helix_about_x(p, 0.2).second;
    lo = std::min(lo, r), hi = std::max(hi, r);
  }
  CHECK(lo >= 0.04 * 0.8 * 0.99);
  CHECK(hi <= 0.04 * 1.2 * 1.01);
  CHECK(hi - lo > 0.04 * 0.3);  // 200 draws from ±20% span most of it
}

TEST_CASE("hair_sketch: clumped strands close on their guides by the requested profile") {
  // A fan of strands falling down from roots on a 10 x 10 patch, spreading toward the tips.
  Strands s;
  for (int a = 0; a < 10; ++a)
    for (int b = 0; b < 10; ++b) {
      const Eigen::Vector3f root(0.1f * a + 0.0037f * b, 0, 0.1f * b + 0.0029f * a * a);  // no ties
      const Eigen::Vector3f dir = Eigen::Vector3f(0.3f * (a - 4.5f) / 4.5f, -1, 0.2f * (b - 4.5f) / 4.5f).normalized();
      for (int i = 0; i <= 30; ++i) s.points.push_back(root + 0.05f * i * dir);
      s.offsets.push_back(static_cast<int>(s.points.size()));
    }
  ClumpDetail c;
  c.clumps = 6;
  c.strength = 0.6;
  c.profile = 2;
  const Strands out = apply_strand_detail(s, {make(c, 7)}, free_context(s.count()));
  std::vector<int> guides;
  for (int i = 0; i < s.count(); ++i)
    if (strand(out, i) == strand(s, i)) guides.push_back(i);
  REQUIRE(guides.size() == 6);
  for (const double t : {0.5, 1.0}) {
    const int at = static_cast<int>(std::lround(30 * t));
    double before = 0, after = 0;
    for (int i = 0; i < s.count(); ++i) {
      int g = guides[0];
      for (const int h : guides)
        if ((s.points[s.offsets[h]] - s.points[s.offsets[i]]).norm() <
            (s.points[s.offsets[g]] - s.points[s.offsets[i]]).norm())
          g = h;
      before += (strand(s, i)[at] - strand(s, g)[at]).norm();
      after += (strand(out, i)[at] - strand(s, g)[at]).norm();
    }
    CAPTURE(t);
    CHECK(after / before == doctest::Approx(1 - 0.6 * t * t).epsilon(1e-4));
  }
}

TEST_CASE("hair_sketch: length variation and a cut line shorten strands as asked") {
  const Strands s = straight_strands(100, -Eigen::Vector3f::UnitY());
  const Strands varied = apply_strand_detail(s, {make(LengthDetail{0.4}, 3)}, free_context(100));
  double shortest = 1, longest = 0;
  for (int i = 0; i < varied.count(); ++i) {
    const auto p = strand(varied, i);
    const double fraction = (p.back() - p.front()).norm() / 2.0;
    shortest = std::min(shortest, fraction), longest = std::max(longest, fraction);
  }
  CHECK(shortest >= 0.6 - 1e-5);
  CHECK(longest <= 1 + 1e-5);
  CHECK(longest - shortest > 0.3);

  // Seen from +z with an identity projection, pixel row 600 of an 800-pixel view is y = -0.5.
  CutDetail cut;
  cut.camera.view(2, 3) = -5;
  cut.camera.viewport = Eigen::Vector4d(0, 0, 800, 800);
  cut.line = {Eigen::Vector2d(0, 600), Eigen::Vector2d(400, 590), Eigen::Vector2d(800, 600)};
  Strands narrow;  // strands within x, z of the view: along z at x = 0
  for (int k = 0; k < 5; ++k) {
    for (int i = 0; i <= 40; ++i) narrow.points.emplace_back(0.f, -0.05f * i, 0.1f * k);
    narrow.offsets.push_back(static_cast<int>(narrow.points.size()));
  }
  const Strands cut_strands = apply_strand_detail(narrow, {make(cut, 1)}, free_context(5));
  // The line passes x = 0 at row 590: y = 1 - 590 / 400.
  for (int i = 0; i < cut_strands.count(); ++i)
    CHECK(strand(cut_strands, i).back().y() == doctest::Approx(-0.475).epsilon(1e-4));
}

TEST_CASE("hair_sketch: zero amplitude is no detail, bit for bit; a region limits a detail to its strands") {
  const Strands s = straight_strands(20, Eigen::Vector3f::UnitX());
  FrizzDetail frizz;
  frizz.amplitude = 0;
  ClumpDetail clump;
  clump.strength = 0;
  const Strands out = apply_strand_detail(s, {curl(5, 0), make(frizz), make(clump)}, free_context(20));
  CHECK(out.points == s.points);
  CHECK(out.offsets == s.offsets);

  DetailContext c = free_context(20);
  for (int i = 0; i < 20; ++i) c.root_vertex[i] = i % 4;  // four root "vertices"
  StrandDetail in_region = curl(5, 0.04);
  in_region.region = {1, 2};
  const Strands limited = apply_strand_detail(s, {in_region}, c);
  for (int i = 0; i < 20; ++i) CHECK((strand(limited, i) == strand(s, i)) == (i % 4 == 0 || i % 4 == 3));
}

TEST_CASE("hair_sketch: detail parameters out of their domain are typed errors naming them") {
  const Strands s = straight_strands(1, Eigen::Vector3f::UnitX());
  CHECK_THROWS_WITH_AS(apply_strand_detail(s, {curl(NAN, 0.1)}, free_context(1)), doctest::Contains("curl frequency"),
                       lapis::InvalidArgument);
  CHECK_THROWS_WITH_AS(apply_strand_detail(s, {curl(5, -1)}, free_context(1)), doctest::Contains("curl radius"),
                       lapis::InvalidArgument);
  CHECK_THROWS_WITH_AS(apply_strand_detail(s, {make(CutDetail{})}, free_context(1)), doctest::Contains("two points"),
                       lapis::InvalidArgument);
  CHECK_THROWS_WITH_AS(apply_strand_detail(s, {make(ClumpDetail{0})}, free_context(1)),
                       doctest::Contains("clump count"), lapis::InvalidArgument);
  CHECK_THROWS_WITH_AS(apply_strand_detail(s, {curl(5, 0.1)}, free_context(2)), doctest::Contains("2 strands"),
                       lapis::InvalidArgument);
  StrandDetail outside = curl(5, 0.1);
  outside.region = {-1};
  CHECK_THROWS_WITH_AS(check_detail(outside, 10, "f"), doctest::Contains("region vertex -1"), lapis::InvalidArgument);
}

namespace {

// Hair combed down the back of the bundled head, with scalp avoidance, on a small grid.
struct GrownHair {
  Grid grid;
  std::vector<Eigen::Vector3d> roots;
  Strands strands;  // grown as the thesis does, without the head check
};
const GrownHair& grown_hair() {
  static const GrownHair hair = [] {
    GrownHair h;
    const Head& head = bundled_head();
    h.grid = small_grid(20000);
    StreamCurve c;
    for (int i = 0; i <= 20; ++i) {
      const double a = 0.25 + 1.6 * i / 20.0;
      c.points.emplace_back(0.35, 1.25 * std::cos(a), -1.25 * std::sin(a));
    }
    std::vector<std::vector<Constraint>> style{c.constraints(h.grid)};
    const ConstraintSet first = ConstraintSet::merge(style);
    auto solver = make_field_solver(h.grid, FieldMethod::Thesis);
    solver->apply(diff(ConstraintSet(), first), first);
    style.push_back(scalp_avoidance_constraints(h.grid, solver->field(), head));
    const ConstraintSet second = ConstraintSet::merge(style);
    solver->apply(diff(first, second), second);
    RootOptions ro;
    ro.count = 3000;
    h.roots = sample_roots(head, ro);
    h.strands = grow_strands(SampledField(h.grid, solver->field()), h.roots);
    return h;
  }();
  return hair;
}

std::vector<StrandDetail> every_detail() {
  CurlDetail c;
  c.radius = 0.05;
  FrizzDetail f;
  f.amplitude = 0.02;
  return {make(ClumpDetail{}, 2), make(c, 3), make(f, 4), make(LengthDetail{}, 5)};
}

}  // namespace

TEST_CASE("hair_sketch: detail on grown hair is the same on 1 and 2 threads and for the same seed") {
  const GrownHair& h = grown_hair();
  const HeadClearance clearance(bundled_head(), h.grid);
  const DetailContext context = detail_context(bundled_head(), h.roots, &clearance);
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const Strands one = apply_strand_detail(h.strands, every_detail(), context);
  omp_set_num_threads(2);
  const Strands two = apply_strand_detail(h.strands, every_detail(), context);
  omp_set_num_threads(threads);
  CHECK(one.points == two.points);
  CHECK(one.offsets == two.offsets);
  auto reseeded = every_detail();
  reseeded[1].seed = 99;
  CHECK(apply_strand_detail(h.strands, reseeded, context).points != one.points);
}

TEST_CASE("hair_sketch: detail starts every strand at its root and sinks no more segments into the head") {
  const GrownHair& h = grown_hair();
  const Head& head = bundled_head();
  const HeadClearance clearance(head, h.grid);
  const DetailContext context = detail_context(head, h.roots, &clearance);
  const Strands out = apply_strand_detail(h.strands, every_detail(), context);
  REQUIRE(out.count() == h.strands.count());
  int moved = 0;
  for (int i = 0; i < out.count(); ++i) {
    CHECK(out.points[out.offsets[i]] == h.strands.points[h.strands.offsets[i]]);
    moved += strand(out, i) != strand(h.strands, i);
  }
  CHECK(moved > 0.9 * out.count());
  const int before = count_penetrating_segments(h.strands, head);
  const int after = count_penetrating_segments(out, head);
  // Detail resamples strands finer, so compare fractions of segments.
  const double before_fraction = double(before) / h.strands.segments();
  const double after_fraction = double(after) / out.segments();
  MESSAGE("penetrating segments: " << before << " of " << h.strands.segments() << " grown, " << after << " of "
                                   << out.segments() << " with detail");
  CHECK(after_fraction <= before_fraction + 1e-3);

  // Without the clearance the same curls sink strands into the scalp: the check is doing work.
  DetailContext unchecked = context;
  unchecked.clearance = nullptr;
  const Strands sunk = apply_strand_detail(h.strands, every_detail(), unchecked);
  CHECK(double(count_penetrating_segments(sunk, head)) / sunk.segments() > after_fraction + 1e-3);
}
