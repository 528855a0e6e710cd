#include <doctest/doctest.h>

#include "lapis/geometry/connectivity.h"
#include "lapis/geometry/procedural.h"
#include "lapis/viewer/loop_picking.h"

using namespace lapis;

TEST_CASE("viewer: loop picking finds the loop and vertex under the cursor and skips hidden ones") {
  // An open cylinder along y seen from the side: its two rims are loops 0 and 1; the nearer half
  // of each rim is visible, the far half is hidden by the wall.
  geometry::TriMesh c = geometry::make_cylinder(32, 8, 1.0, 2.0);
  for (int v = 0; v < c.num_vertices(); ++v) std::swap(c.V(v, 1), c.V(v, 2));  // axis z -> y
  const geometry::Connectivity conn(c);
  const auto& loops = conn.boundary_loops();
  REQUIRE(loops.size() == 2);
  const geometry::Bvh bvh(c);
  const auto cam = geometry::look_at_camera({0, 1.5, 6}, {0, 1, 0}, Eigen::Vector3d::UnitY(), 0.8, 800, 600);
  for (size_t l = 0; l < 2; ++l) {
    // The rim vertex facing the camera (largest z).
    const auto& loop = loops[l];
    const int front = *std::max_element(loop.begin(), loop.end(), [&](int a, int b) { return c.V(a, 2) < c.V(b, 2); });
    const Eigen::Vector3d s = geometry::project(cam, c.V.row(front).transpose());
    const viewer::LoopPick near = viewer::pick_loop(cam, c.V, loops, s.x() + 3, s.y() + 2, 10, {&bvh});
    REQUIRE(near);
    CHECK(near.loop == static_cast<int>(l));
    const viewer::LoopPick v = viewer::pick_loop_vertex(cam, c.V, loops, s.x() + 1, s.y(), 10, {&bvh});
    CHECK(v.vertex == front);
    CHECK(v.pixels < 2);
    // The same pixel, with this loop excluded, picks nothing (the other rim is far away).
    CHECK(!viewer::pick_loop(cam, c.V, loops, s.x(), s.y(), 10, {&bvh}, {1 - static_cast<int>(l)}));
  }
  // The far side of the rim, behind the wall: hidden.
  const int back =
      *std::min_element(loops[0].begin(), loops[0].end(), [&](int a, int b) { return c.V(a, 2) < c.V(b, 2); });
  CHECK(!viewer::visible(cam, c.V.row(back).transpose(), {&bvh}));
  CHECK(viewer::visible(cam, c.V.row(back).transpose(), {}));
  // Far from every loop: nothing.
  CHECK(!viewer::pick_loop(cam, c.V, loops, 5, 5, 10, {&bvh}));
}
