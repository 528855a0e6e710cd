// triangulate_polygon(): the max-min-angle triangulation, checked against every triangulation
// of small polygons.
#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <functional>
#include <numbers>
#include <random>

#include "lapis/core/error.h"
#include "lapis/geometry/mesh_edit.h"

using namespace lapis::geometry;

namespace {

double smallest_angle_deg(const Vertices& V, int a, int b, int c) {
  double m = 180;
  const int t[3] = {a, b, c};
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d p = V.row(t[k]).transpose();
    const Eigen::Vector3d u = V.row(t[(k + 1) % 3]).transpose() - p, w = V.row(t[(k + 2) % 3]).transpose() - p;
    m = std::min(m, std::atan2(u.cross(w).norm(), u.dot(w)) * 180 / std::numbers::pi);
  }
  return m;
}

double smallest_angle_deg(const Vertices& V, const Faces& F) {
  double m = 180;
  for (Eigen::Index f = 0; f < F.rows(); ++f) m = std::min(m, smallest_angle_deg(V, F(f, 0), F(f, 1), F(f, 2)));
  return m;
}

// The best smallest angle over all triangulations of corners i..j (brute force, Catalan many).
double best_by_enumeration(const Vertices& V, const std::vector<int>& p, size_t i, size_t j) {
  if (j < i + 2) return 180;
  double best = -1;
  for (size_t m = i + 1; m < j; ++m)
    best = std::max(best, std::min({smallest_angle_deg(V, p[i], p[m], p[j]), best_by_enumeration(V, p, i, m),
                                    best_by_enumeration(V, p, m, j)}));
  return best;
}

// A triangle with `per_side` points inserted along each of its sides (the polygon a seam
// makes of a face whose edges get new vertices), corners jittered a little.
Vertices triangle_with_points(int per_side, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  const Eigen::RowVector3d c[3] = {{0 + u(rng), 0, 0}, {1, 0 + u(rng), 0}, {0.4 + u(rng), 0.9, 0}};
  Vertices V(3 * (per_side + 1), 3);
  int n = 0;
  for (int s = 0; s < 3; ++s)
    for (int k = 0; k <= per_side; ++k) {
      const double t = k == 0 ? 0.0 : (k + 0.3 * u(rng)) / (per_side + 1);
      V.row(n++) = (1 - t) * c[s] + t * c[(s + 1) % 3];
    }
  return V;
}

}  // namespace

TEST_CASE("geometry: triangulating a polygon maximizes the smallest angle, as enumerating every triangulation does") {
  for (unsigned seed = 0; seed < 10; ++seed)
    for (int per_side : {0, 1, 2}) {
      const Vertices V = triangle_with_points(per_side, seed);
      std::vector<int> polygon(static_cast<size_t>(V.rows()));
      for (size_t k = 0; k < polygon.size(); ++k) polygon[k] = static_cast<int>(k);
      const Faces F = triangulate_polygon(V, polygon);
      REQUIRE(F.rows() == V.rows() - 2);
      const double best = best_by_enumeration(V, polygon, 0, polygon.size() - 1);
      CHECK(smallest_angle_deg(V, F) == doctest::Approx(best).epsilon(1e-9));
      CHECK(best > 1.0);  // no triangle spans three points of one side
      // The polygon winds counter-clockwise in the xy-plane, and so does every triangle.
      for (Eigen::Index f = 0; f < F.rows(); ++f) {
        const Eigen::Vector3d a = V.row(F(f, 0)).transpose(), b = V.row(F(f, 1)).transpose(),
                              c = V.row(F(f, 2)).transpose();
        CHECK((b - a).cross(c - a).z() > 0);
      }
    }
}

TEST_CASE("geometry: a similarity of the polygon does not change its triangles") {
  const Vertices V = triangle_with_points(3, 7);
  std::vector<int> polygon(static_cast<size_t>(V.rows()));
  for (size_t k = 0; k < polygon.size(); ++k) polygon[k] = static_cast<int>(k);
  const Faces F = triangulate_polygon(V, polygon);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Vertices moved = ((3.7 * V * R.transpose()).rowwise() + Eigen::RowVector3d(5, -2, 9)).eval();
  CHECK(triangulate_polygon(moved, polygon) == F);
}

TEST_CASE("geometry: a long polygon is fanned from its best corner") {
  // 200 points along one side of a triangle: only the fan from the opposite corner has no
  // degenerate triangle.
  const int n = 200;
  Vertices V(n + 1, 3);
  for (int k = 0; k < n; ++k) V.row(k) << double(k) / (n - 1), 0, 0;
  V.row(n) << 0.5, 1, 0;
  std::vector<int> polygon(n + 1);
  for (int k = 0; k <= n; ++k) polygon[k] = k;
  const Faces F = triangulate_polygon(V, polygon);
  REQUIRE(F.rows() == n - 1);
  for (Eigen::Index f = 0; f < F.rows(); ++f) CHECK((F.row(f).array() == n).any());
  CHECK(smallest_angle_deg(V, F) > 0.1);
}

TEST_CASE("geometry: triangulating a polygon rejects fewer than three corners and bad indices") {
  const Vertices V = Vertices::Zero(4, 3);
  CHECK_THROWS_WITH_AS(triangulate_polygon(V, {0, 1}),
                       "geometry::triangulate_polygon(): polygon has 2 corners, expected at least 3",
                       lapis::InvalidArgument);
  CHECK_THROWS_WITH_AS(triangulate_polygon(V, {0, 1, 4}),
                       "geometry::triangulate_polygon(): vertex 4 out of range [0, 4)", lapis::InvalidArgument);
}
