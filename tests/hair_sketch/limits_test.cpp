// One number must not hang the machine or exhaust its memory: curve sampling, ponytail
// sections and strand growth estimate their work before they start and refuse with it.
#include <doctest/doctest.h>

#include <chrono>

#include "fixture.h"
#include "lapis/hair_sketch/ponytail.h"
#include "lapis/hair_sketch/stream_curve.h"
#include "lapis/hair_sketch/style_field.h"

using namespace hair_test;

namespace {

// The ponytail of the style tests: a spine down the back of the head, a ring of radius 0.3.
Ponytail back_ponytail() {
  const Head& head = bundled_head();
  Ponytail pt;
  const Eigen::Vector3d start = head.center + Eigen::Vector3d(0, 0.1, -1.15);
  const Eigen::Vector3d dir = Eigen::Vector3d(0, -0.55, -0.83).normalized();
  for (int i = 0; i <= 12; ++i) pt.spine.push_back(start + 0.2 * i * dir);
  const Eigen::Vector3d c1 = start + 0.5 * dir;
  const Eigen::Vector3d u = dir.cross(Eigen::Vector3d::UnitX()).normalized(), v = dir.cross(u);
  for (int k = 0; k < 16; ++k) {
    const double a = 2 * 3.14159265 * k / 16;
    pt.cross_section.push_back(c1 + 0.3 * (std::cos(a) * u + std::sin(a) * v));
  }
  for (int i = 0; i <= 6; ++i) {
    const Eigen::Vector3d c = c1 + 0.15 * i * dir;
    pt.profile_a.push_back(c + (0.3 - 0.015 * i) * Eigen::Vector3d::UnitX());
    pt.profile_b.push_back(c - (0.3 - 0.015 * i) * Eigen::Vector3d::UnitX());
  }
  return pt;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

TEST_CASE("hair_sketch: a curve point far from the others is refused before sampling") {
  const Grid g = small_grid();
  const auto t0 = std::chrono::steady_clock::now();
  Ponytail pt = back_ponytail();
  CHECK_FALSE(pt.constraints(g).empty());
  pt.spine.back() = Eigen::Vector3d(-1e308, 0, 0);
  CHECK_THROWS_WITH_AS(pt.constraints(g),
                       doctest::Contains("hair_sketch::Ponytail::constraints(): a curve of length inf at spacing"),
                       lapis::ResourceLimit);
  StreamCurve c;
  c.points = {Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 1e12, 0)};
  CHECK_THROWS_WITH_AS(c.constraints(g), doctest::Contains("samples, at most 1.04858e+06 allowed"),
                       lapis::ResourceLimit);
  CHECK(seconds_since(t0) < 5);
}

TEST_CASE("hair_sketch: a ponytail section of radius 1e9 is refused with its estimate") {
  const Grid g = small_grid();
  const auto t0 = std::chrono::steady_clock::now();
  Ponytail pt = back_ponytail();
  pt.cross_section[3] *= 1e9;  // one point: the mean radius becomes about 6e7
  CHECK_THROWS_WITH_AS(pt.constraints(g),
                       doctest::Contains("hair_sketch::Ponytail::constraints(): the cross sections need"),
                       lapis::ResourceLimit);
  pt = back_ponytail();
  // One profile far out beside the spine: radii of 5e5 along the ponytail, rings of 1.7e7 points.
  for (Eigen::Vector3d& p : pt.profile_a) p += 1e6 * Eigen::Vector3d::UnitX();
  CHECK_THROWS_AS(pt.constraints(g), lapis::ResourceLimit);
  CHECK(seconds_since(t0) < 5);
}

TEST_CASE("hair_sketch: settings whose strands would not fit in memory are refused before the grid") {
  const Head& head = bundled_head();
  HairstyleSettings s;
  s.grid.target_unknowns = 8000;
  CHECK_NOTHROW(hairstyle_grid(head, s));
  CHECK(estimate_strand_bytes(s.roots.count, s.growth) < 100e6);  // the defaults: tens of MB
  const auto t0 = std::chrono::steady_clock::now();
  s.roots.count = 10'000'000;  // the largest a session allows: 10M strands of 241 points
  CHECK_THROWS_WITH_AS(
      hairstyle_grid(head, s),
      doctest::Contains("hair_sketch::hairstyle_grid(): 1e+07 strands of up to 240 steps (max_length 120 / "
                        "step 0.5) may have 2.41e+09 points"),
      lapis::ResourceLimit);
  s.roots.count = 2'000'000;
  CHECK_THROWS_WITH_AS(hairstyle_grid(head, s), doctest::Contains("MiB, more than the limit of 4096 MiB"),
                       lapis::ResourceLimit);
  s.roots.count = 5000;
  s.growth.step = 0.001;
  s.growth.max_length = 1e6;  // 1e9 steps a strand
  CHECK_THROWS_AS(hairstyle_grid(head, s), lapis::ResourceLimit);
  Hairstyle style;
  style.settings = s;
  CHECK_THROWS_AS(build_hairstyle(style, head), lapis::ResourceLimit);
  CHECK(seconds_since(t0) < 5);
}
