#include <doctest/doctest.h>

#include <algorithm>

#include "lapis/core/error.h"
#include "lapis/geometry/procedural.h"
#include "lapis/viewer/surface_select.h"

using namespace lapis;
using namespace lapis::viewer;

namespace {

geometry::CameraMatrices front_camera(double z = 4) {
  return geometry::look_at_camera({0, 0, z}, {0, 0, 0}, Eigen::Vector3d::UnitY(), 0.8, 800, 600);
}

bool contains(const std::vector<int>& s, int v) { return std::binary_search(s.begin(), s.end(), v); }

}  // namespace

TEST_CASE("viewer: point in polygon, convex and concave, even-odd") {
  const std::vector<Eigen::Vector2d> square{{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  CHECK(point_in_polygon(square, {5, 5}));
  CHECK(!point_in_polygon(square, {15, 5}));
  CHECK(!point_in_polygon(square, {5, -1}));
  // A U shape: the notch is outside.
  const std::vector<Eigen::Vector2d> u{{0, 0}, {30, 0}, {30, 30}, {20, 30}, {20, 10}, {10, 10}, {10, 30}, {0, 30}};
  CHECK(point_in_polygon(u, {5, 20}));
  CHECK(point_in_polygon(u, {25, 20}));
  CHECK(!point_in_polygon(u, {15, 20}));
  CHECK(point_in_polygon(u, {15, 5}));
  CHECK(!point_in_polygon({{0, 0}, {1, 1}}, {0.5, 0.5}));  // not a polygon
}

TEST_CASE("viewer: the lasso takes the sphere's front vertices inside the polygon, not the hidden back ones") {
  const geometry::TriMesh sphere = geometry::make_icosphere(3);
  const geometry::Bvh bvh(sphere);
  const auto cam = front_camera();
  // A square around the screen centre, half the sphere's screen radius wide.
  const Eigen::Vector2d c(400, 300);
  const double h = 60;
  const std::vector<Eigen::Vector2d> lasso{c + Eigen::Vector2d(-h, -h), c + Eigen::Vector2d(h, -h),
                                           c + Eigen::Vector2d(h, h), c + Eigen::Vector2d(-h, h)};
  const std::vector<int> visible = lasso_vertices(sphere, bvh, cam, lasso);
  const std::vector<int> all = lasso_vertices(sphere, bvh, cam, lasso, {.visible_only = false});
  REQUIRE(!visible.empty());
  CHECK(all.size() > visible.size());
  for (int v : visible) CHECK(sphere.V(v, 2) > 0);  // front half only
  int back = 0;
  for (int v : all) back += sphere.V(v, 2) < 0;
  CHECK(back > 0);
  // Exactly the front vertices whose projection is inside.
  for (int v = 0; v < sphere.num_vertices(); ++v) {
    const Eigen::Vector3d s = geometry::project(cam, sphere.V.row(v).transpose());
    const bool inside = std::abs(s.x() - c.x()) < h && std::abs(s.y() - c.y()) < h;
    if (sphere.V(v, 2) > 0.05) CHECK(contains(visible, v) == inside);
  }
}

TEST_CASE("viewer: the brush paints a disc under the cursor and stays on the sheet it hit") {
  // Two parallel sheets 0.05 apart: the brush's ball reaches the back sheet, the flood fill
  // through the front sheet's edges does not.
  geometry::TriMesh front = geometry::make_plane_grid(40, 40, 2, 2);
  front.V.col(0).array() -= 1, front.V.col(1).array() -= 1;  // centred on the view axis
  geometry::TriMesh back = front;
  back.V.col(2).array() -= 0.05;
  geometry::TriMesh both;
  both.V.resize(front.V.rows() * 2, 3);
  both.V << front.V, back.V;
  both.F.resize(front.F.rows() * 2, 3);
  both.F << front.F, (back.F.array() + static_cast<int>(front.V.rows())).matrix();
  REQUIRE(front.V.col(2).cwiseAbs().maxCoeff() == 0);  // the grid lies in z = 0
  const geometry::Bvh bvh(both);
  const geometry::Connectivity conn(both);
  const auto cam = front_camera();
  const std::vector<int> painted = brush_vertices(both, conn, bvh, cam, {400, 300}, {.radius_px = 40});
  REQUIRE(painted.size() > 10);
  // World radius of 40 px at depth 4 with a 0.8 rad field of view over 600 px.
  const double radius = 40 * (2 * 4 * std::tan(0.4) / 600);
  for (int v : painted) {
    CHECK(v < front.V.rows());
    CHECK(both.V.row(v).head<2>().norm() <= radius + 1e-9);
  }
  // Every front vertex well inside the disc is painted.
  for (int v = 0; v < front.V.rows(); ++v)
    if (front.V.row(v).head<2>().norm() < 0.9 * radius) CHECK(contains(painted, v));
  // Missing the surface paints nothing.
  CHECK(brush_vertices(both, conn, bvh, cam, {5, 5}).empty());
}

TEST_CASE("viewer: the x-ray brush paints every vertex under its circle, the sphere's back too") {
  const geometry::TriMesh sphere = geometry::make_icosphere(3);
  const geometry::Bvh bvh(sphere);
  const geometry::Connectivity conn(sphere);
  const auto cam = front_camera();
  const Eigen::Vector2d c(400, 300);
  const std::vector<int> surface = brush_vertices(sphere, conn, bvh, cam, c, {.radius_px = 50});
  const std::vector<int> xray = brush_vertices(sphere, conn, bvh, cam, c, {.radius_px = 50, .through = true});
  REQUIRE(!surface.empty());
  for (int v : surface) CHECK(sphere.V(v, 2) > 0);  // the plain brush: the front only
  // X-ray: exactly the vertices whose projection is within the radius, front and back.
  int back = 0;
  for (int v = 0; v < sphere.num_vertices(); ++v) {
    const Eigen::Vector3d s = geometry::project(cam, sphere.V.row(v).transpose());
    CHECK(contains(xray, v) == ((s.head<2>() - c).norm() <= 50));
    back += contains(xray, v) && sphere.V(v, 2) < 0;
  }
  CHECK(back > static_cast<int>(surface.size()) / 2);
  CHECK(std::includes(xray.begin(), xray.end(), surface.begin(), surface.end()));
  // Beside the sphere it paints nothing, as the plain brush does.
  CHECK(brush_vertices(sphere, conn, bvh, cam, {5, 5}, {.radius_px = 50, .through = true}).empty());
}

TEST_CASE("viewer: grow then shrink by rings restores a set's interior; shrink of everything keeps it") {
  const geometry::TriMesh grid = geometry::make_plane_grid(20, 20);
  const geometry::Connectivity conn(grid);
  const std::vector<int> seed{21 * 10 + 10};  // a middle vertex
  const std::vector<int> ring2 = grow_rings(conn, seed, 2);
  CHECK(ring2.size() > 10);
  CHECK(grow_rings(conn, seed, 0) == seed);
  CHECK(shrink_rings(conn, ring2, 2) == seed);
  CHECK(shrink_rings(conn, ring2, 5).empty());
  CHECK(shrink_rings(conn, grow_rings(conn, ring2, 1), 1) == ring2);
  CHECK_THROWS_AS(grow_rings(conn, {100000}, 1), lapis::InvalidArgument);
}
