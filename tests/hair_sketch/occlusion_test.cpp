// Hair self-shadowing by density: a uniform slab of hair is Beer–Lambert's law, the light does
// not depend on how many strands stand for the hair, and bad options are named.
#include <doctest/doctest.h>

#include <cmath>

#include "lapis/core/error.h"
#include "lapis/hair_sketch/strand_occlusion.h"

using namespace lapis::hair_sketch;

namespace {

// Straight strands along x through the unit cube, on a `per_side`² lattice in (y, z):
// a slab of uniform density.
Strands slab(int per_side, int every = 1) {
  Strands s;
  for (int j = 0; j < per_side; ++j)
    for (int k = 0; k < per_side; ++k) {
      if ((j * per_side + k) % every) continue;
      const float y = (static_cast<float>(j) + 0.5f) / static_cast<float>(per_side);
      const float z = (static_cast<float>(k) + 0.5f) / static_cast<float>(per_side);
      for (int i = 0; i <= 40; ++i) s.points.emplace_back(static_cast<float>(i) / 40.0f, y, z);
      s.offsets.push_back(static_cast<int>(s.points.size()));
    }
  return s;
}

}  // namespace

TEST_CASE("occlusion: light from above through a uniform slab falls as exp(-depth / shadow_depth)") {
  const Strands hair = slab(100);
  StrandOcclusionOptions o;
  o.sky_weight = 1;
  o.shadow_depth = 0.3;
  o.cells_across = 32;
  const StrandOcclusion occlusion(hair, o);
  float previous = 2;
  for (const float depth : {0.1f, 0.25f, 0.5f, 0.75f, 0.9f}) {
    const float t = occlusion.transmittance(Eigen::Vector3f(0.5f, 1.0f - depth, 0.5f));
    CAPTURE(depth);
    // Within 3%: the splat blurs the slab's top edge over one cell.
    CHECK(t == doctest::Approx(std::exp(-depth / 0.3f)).epsilon(0.03));
    CHECK(t < previous);
    previous = t;
  }
  CHECK(occlusion.transmittance(Eigen::Vector3f(0.5f, 3.0f, 0.5f)) == 1.0f);  // outside the hair
}

TEST_CASE("occlusion: side light reaches the slab's edges more than its core") {
  StrandOcclusionOptions o;
  o.sky_weight = 0;
  o.shadow_depth = 0.1;
  const StrandOcclusion occlusion(slab(60), o);
  const float core = occlusion.transmittance(Eigen::Vector3f(0.5f, 0.5f, 0.5f));
  const float edge = occlusion.transmittance(Eigen::Vector3f(0.5f, 0.5f, 0.02f));
  CHECK(core < 0.05f);  // 0.5 deep from every side: 4 · exp(−5) / 4
  CHECK(edge > 0.15f);  // 0.02 deep from one of four sides: exp(−0.2) / 4
}

TEST_CASE("occlusion: the light does not depend on how many strands stand for the hair") {
  const StrandOcclusion all(slab(80)), half(slab(80, 2));
  for (const float y : {0.2f, 0.5f, 0.8f}) {
    const Eigen::Vector3f p(0.4f, y, 0.6f);
    CHECK(half.transmittance(p) == doctest::Approx(all.transmittance(p)).epsilon(0.05));
  }
  // And per point of any strands: the strands' own points.
  const Strands hair = slab(20);
  const std::vector<float> t = all.transmittance(hair);
  REQUIRE(t.size() == hair.points.size());
  CHECK(t[123] == all.transmittance(hair.points[123]));
}

TEST_CASE("occlusion: no hair is fully lit; bad options and points are named") {
  const StrandOcclusion none{Strands{}};
  CHECK(none.transmittance(Eigen::Vector3f::Zero()) == 1.0f);
  const Strands hair = slab(4);
  auto occlusion = [](const Strands& s, const StrandOcclusionOptions& o) { return StrandOcclusion(s, o); };
  StrandOcclusionOptions o;
  o.shadow_depth = 0;
  CHECK_THROWS_WITH_AS(occlusion(hair, o), doctest::Contains("shadow_depth"), lapis::Error);
  o = {};
  o.sky_weight = 1.5;
  CHECK_THROWS_WITH_AS(occlusion(hair, o), doctest::Contains("sky_weight"), lapis::Error);
  o = {};
  o.cell = 1e-6;
  CHECK_THROWS_WITH_AS(occlusion(hair, o), doctest::Contains("cell"), lapis::Error);
  Strands bad = hair;
  bad.points[3].x() = NAN;
  CHECK_THROWS_WITH_AS(occlusion(bad, {}), doctest::Contains("not finite"), lapis::Error);
}
