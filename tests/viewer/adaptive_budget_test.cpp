#include <doctest/doctest.h>

#include "lapis/viewer/adaptive_budget.h"

using lapis::viewer::AdaptiveBudget;

TEST_CASE("viewer: the adaptive budget shrinks after slow frames in proportion to the overshoot") {
  AdaptiveBudget b(200000, {.target_ms = 80, .minimum = 20000});
  CHECK_FALSE(b.observe(400, 4000000));  // one slow frame (an upload, say) is not enough
  CHECK(b.value() == 200000);
  CHECK(b.observe(400, 4000000));
  CHECK(b.value() == 40000);  // 80 / 400 of it
  CHECK_FALSE(b.observe(2000, 4000000));
  CHECK(b.observe(2000, 4000000));
  CHECK(b.value() == 20000);  // never below the minimum
  CHECK_FALSE(b.observe(2000, 4000000));
  CHECK_FALSE(b.observe(2000, 4000000));
}

TEST_CASE("viewer: the adaptive budget grows back after many fast frames, up to full detail") {
  AdaptiveBudget b(100000, {.target_ms = 80, .fast_frames = 3, .growth = 1.5});
  CHECK_FALSE(b.observe(10, 1000000));
  CHECK_FALSE(b.observe(10, 1000000));
  CHECK(b.observe(10, 1000000));
  CHECK(b.value() == 150000);
  CHECK_FALSE(b.observe(60, 1000000));  // neither fast nor slow: resets the count
  CHECK_FALSE(b.observe(10, 1000000));
  CHECK_FALSE(b.observe(10, 1000000));
  CHECK(b.observe(10, 160000));
  CHECK(b.value() == 160000);  // capped at what full detail needs
  for (int i = 0; i < 10; ++i) CHECK_FALSE(b.observe(10, 160000));
}

TEST_CASE("viewer: a pinned budget does not adapt") {
  AdaptiveBudget b(200000);
  b.pin(0);
  for (int i = 0; i < 5; ++i) CHECK_FALSE(b.observe(5000, 4000000));
  CHECK(b.value() == 0);
  CHECK(b.pinned());
}
