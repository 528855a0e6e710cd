#include <doctest/doctest.h>

#include <cmath>

#include "lapis/viewer/colormap.h"

using namespace lapis::viewer;

TEST_CASE("viewer: the colour map runs from blue to red, clamps, and greys out NaN") {
  const Eigen::Vector3f lo = colormap(0), hi = colormap(1);
  CHECK(lo.z() > lo.x());  // blue end
  CHECK(hi.x() > hi.z());  // red end
  CHECK((colormap(-3) - lo).norm() == 0);
  CHECK((colormap(7) - hi).norm() == 0);
  CHECK(colormap(std::nan("")).x() == doctest::Approx(0.5));
  // Continuous: neighbouring values give neighbouring colours.
  for (double t = 0; t < 1; t += 0.01) CHECK((colormap(t + 0.01) - colormap(t)).norm() < 0.1);
  Eigen::VectorXd v(3);
  v << 0, 5, 10;
  const Points3f c = colorize(v, 0, 10);
  CHECK((Eigen::Vector3f(c.row(0)) - lo).norm() == 0);
  CHECK((Eigen::Vector3f(c.row(2)) - hi).norm() == 0);
}

TEST_CASE("viewer: percentile ignores non-finite values") {
  Eigen::VectorXd v(101);
  for (int i = 0; i <= 100; ++i) v(i) = i;
  CHECK(percentile(v, 0.95) == doctest::Approx(95));
  v(3) = std::nan("");
  CHECK(percentile(v, 1.0) == 100);
  CHECK(percentile(Eigen::VectorXd(), 0.5) == 0);
}
