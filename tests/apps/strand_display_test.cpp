#include <doctest/doctest.h>

#include <random>

#include "lapis/core/error.h"
#include "strand_display.h"

using namespace lapis;
using namespace lapis::hair_app;
using lapis::hair_sketch::Strands;

namespace {

// `count` strands of random lengths (2..max_points points) along distinct lines.
Strands random_strands(int count, int max_points, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> length(2, max_points);
  Strands s;
  for (int k = 0; k < count; ++k) {
    const int n = length(rng);
    for (int i = 0; i < n; ++i) s.points.emplace_back(static_cast<float>(k), static_cast<float>(i), 0.0f);
    s.offsets.push_back(static_cast<int>(s.points.size()));
  }
  return s;
}

}  // namespace

TEST_CASE("hair_app: display strands within budget are the strands themselves") {
  const Strands s = random_strands(50, 40, 1);
  std::vector<int> kept;
  const Strands d = display_strands(s, {.max_segments = s.segments(), .max_points_per_strand = 8}, &kept);
  CHECK(d.points == s.points);
  CHECK(d.offsets == s.offsets);
  CHECK(kept.size() == 50);
  CHECK(display_strands(s, {.max_segments = 0}).points.size() == s.points.size());
}

TEST_CASE("hair_app: display strands meet the budget with decimated, evenly spread strands") {
  const Strands s = random_strands(20000, 200, 2);
  for (int budget : {1000, 50000, 150000}) {
    CAPTURE(budget);
    std::vector<int> kept;
    const Strands d = display_strands(s, {.max_segments = budget, .max_points_per_strand = 32}, &kept);
    CHECK(d.segments() <= budget * 11 / 10);
    CHECK(d.segments() >= budget * 8 / 10);  // the budget is used, not wasted
    REQUIRE(static_cast<int>(kept.size()) == d.count());
    CHECK(std::is_sorted(kept.begin(), kept.end()));
    CHECK(std::adjacent_find(kept.begin(), kept.end()) == kept.end());
    CHECK(kept.front() == 0);
    CHECK(kept.back() >= 20000 - 20000 / d.count() - 1);  // spread to the last strands
    for (int k = 0; k < d.count(); ++k) {
      const int src = kept[static_cast<size_t>(k)];
      const int a = s.offsets[static_cast<size_t>(src)], b = s.offsets[static_cast<size_t>(src) + 1];
      const int da = d.offsets[static_cast<size_t>(k)], db = d.offsets[static_cast<size_t>(k) + 1];
      CHECK(db - da == std::min(b - a, 32));
      CHECK(d.points[static_cast<size_t>(da)] == s.points[static_cast<size_t>(a)]);          // root kept
      CHECK(d.points[static_cast<size_t>(db) - 1] == s.points[static_cast<size_t>(b) - 1]);  // tip kept
      for (int i = da + 1; i < db; ++i)  // a subsequence of the strand, in order
        CHECK(d.points[static_cast<size_t>(i)].y() > d.points[static_cast<size_t>(i) - 1].y());
    }
  }
  CHECK_THROWS_AS(display_strands(s, {.max_segments = -1}), InvalidArgument);
  CHECK_THROWS_AS(display_strands(s, {.max_segments = 10, .max_points_per_strand = 1}), InvalidArgument);
}

TEST_CASE("hair_app: display strands are every k-th strand, so every k-th strand alone shows the same") {
  // The app draws a preview of every k-th strand before the rest have grown: the picture must
  // be the one the whole set gives.
  const Strands s = random_strands(20000, 200, 3);
  const StrandDisplayOptions options{.max_segments = 20000, .max_points_per_strand = 32};
  const int k = display_stride(s, options);
  CHECK(k > 20);
  std::vector<int> kept;
  const Strands all = display_strands(s, options, &kept);
  REQUIRE(static_cast<int>(kept.size()) == (20000 + k - 1) / k);
  for (int j = 0; j < static_cast<int>(kept.size()); ++j) CHECK(kept[static_cast<size_t>(j)] == j * k);
  CHECK(all.segments() <= options.max_segments);

  Strands every_kth;
  for (int i = 0; i < s.count(); i += k) {
    every_kth.points.insert(every_kth.points.end(), s.points.begin() + s.offsets[static_cast<size_t>(i)],
                            s.points.begin() + s.offsets[static_cast<size_t>(i) + 1]);
    every_kth.offsets.push_back(static_cast<int>(every_kth.points.size()));
  }
  StrandDisplayOptions subset = options;
  subset.stride = 1;
  const Strands shown = display_strands(every_kth, subset);
  CHECK(shown.points == all.points);
  CHECK(shown.offsets == all.offsets);

  // The stride shown now is kept within one of the best, from 8 on; farther, the best is taken.
  StrandDisplayOptions current = options;
  for (int now : {k - 1, k + 1}) {
    current.current_stride = now;
    CHECK(display_stride(s, current) == now);
  }
  current.current_stride = k + 2;
  CHECK(display_stride(s, current) == k);
  current.max_segments = 200000;  // best stride 3: below 8, nothing is kept
  current.current_stride = display_stride(s, current) + 1;
  CHECK(display_stride(s, current) == current.current_stride - 1);
  CHECK(display_stride(s, {.max_segments = 0}) == 1);
  CHECK_THROWS_AS(display_strands(s, {.stride = -1}), InvalidArgument);
}
