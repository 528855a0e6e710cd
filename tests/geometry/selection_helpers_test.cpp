// The selection helpers the apps' tools stand on: connected region, geodesic disc, mirroring,
// nearness to a region's border.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "lapis/core/error.h"
#include "lapis/geometry/connected_region.h"
#include "lapis/geometry/geodesic_disc.h"
#include "lapis/geometry/mirror_vertices.h"
#include "lapis/geometry/procedural.h"
#include "lapis/geometry/region_border.h"

using namespace lapis;
using namespace lapis::geometry;

namespace {

// Two meshes in one: `a` then `b` shifted by `offset`, sharing no vertex.
TriMesh side_by_side(const TriMesh& a, const TriMesh& b, const Eigen::Vector3d& offset) {
  TriMesh m;
  m.V.resize(a.V.rows() + b.V.rows(), 3);
  m.V << a.V, b.V.rowwise() + offset.transpose();
  m.F.resize(a.F.rows() + b.F.rows(), 3);
  m.F << a.F, b.F.array() + static_cast<int>(a.V.rows());
  return m;
}

bool contains(const std::vector<int>& s, int v) { return std::binary_search(s.begin(), s.end(), v); }

}  // namespace

TEST_CASE("geometry: connected_region takes exactly the clicked component, or the part allowed") {
  const TriMesh sphere = make_icosphere(2), torus = make_torus(16, 8);
  const TriMesh both = side_by_side(sphere, torus, {4, 0, 0});
  const Connectivity conn(both);
  const int ns = static_cast<int>(sphere.V.rows()), n = static_cast<int>(both.V.rows());
  const std::vector<int> on_torus = connected_region(conn, ns + 5);
  REQUIRE(static_cast<int>(on_torus.size()) == n - ns);
  CHECK(on_torus.front() == ns);
  CHECK(std::is_sorted(on_torus.begin(), on_torus.end()));
  CHECK(static_cast<int>(connected_region(conn, 3).size()) == ns);
  // Allowed: the sphere's upper cap and a lower cap, apart; the seed's cap only.
  std::vector<char> allowed(static_cast<size_t>(n), 0);
  for (int v = 0; v < ns; ++v) allowed[static_cast<size_t>(v)] = std::abs(both.V(v, 2)) > 0.5;
  int top = 0;
  both.V.topRows(ns).col(2).maxCoeff(&top);
  const std::vector<int> cap = connected_region(conn, top, allowed);
  REQUIRE(!cap.empty());
  for (int v = 0; v < n; ++v) CHECK(contains(cap, v) == (v < ns && both.V(v, 2) > 0.5));
  // A seed that is not allowed: nothing.
  int equator = 0;
  both.V.topRows(ns).col(2).cwiseAbs().minCoeff(&equator);
  CHECK(connected_region(conn, equator, allowed).empty());
  CHECK_THROWS_WITH_AS(connected_region(conn, n), doctest::Contains("geometry::connected_region(): seed"),
                       InvalidArgument);
  CHECK_THROWS_WITH_AS(connected_region(conn, 0, std::vector<char>(3, 1)),
                       doctest::Contains("geometry::connected_region(): allowed has 3 entries"), InvalidArgument);
}

TEST_CASE("geometry: geodesic_disc on a flat grid is a disc of the radius, within Dijkstra's 8%") {
  // A 40 x 40 grid of unit cells with alternating diagonals: every other vertex has eight
  // evenly spread edges, the case the header's bound is for.
  const int n = 40;
  const TriMesh grid = make_irregular_grid(n, n, 0.0, 1, n, n);
  const Connectivity conn(grid);
  const int centre = (n / 2) * (n + 1) + n / 2;
  const Eigen::Vector3d c = grid.V.row(centre).transpose();
  for (double radius : {3.0, 7.5, 12.0}) {
    CAPTURE(radius);
    const std::vector<int> disc = geodesic_disc(grid, conn, centre, radius);
    REQUIRE(contains(disc, centre));
    double farthest = 0;
    for (int v = 0; v < grid.num_vertices(); ++v) {
      const double d = (grid.V.row(v).transpose() - c).norm();
      if (contains(disc, v)) farthest = std::max(farthest, d);
      if (d <= radius / 1.0824) CHECK(contains(disc, v));  // inside the inscribed disc: taken
      if (d > radius + 1e-9) CHECK(!contains(disc, v));    // outside the radius: never
    }
    CHECK(farthest > radius - 1);  // the disc reaches its radius (along the edges' directions)
  }
  // On a curved surface the disc follows the surface: a cap of the sphere, not a ball.
  const TriMesh sphere = make_icosphere(4);
  const Connectivity sc(sphere);
  int top = 0;
  sphere.V.col(2).maxCoeff(&top);
  // 1 rad of arc reaches z = cos 1 = 0.54; chords are 0.03% shorter than their arcs, Dijkstra's
  // paths up to ~10% longer.
  const std::vector<int> cap = geodesic_disc(sphere, sc, top, 1.0);
  for (int v = 0; v < sphere.num_vertices(); ++v) {
    if (sphere.V(v, 2) > 0.65) CHECK(contains(cap, v));
    if (sphere.V(v, 2) < 0.535) CHECK(!contains(cap, v));
  }
  CHECK(geodesic_disc(sphere, sc, top, 0.0) == std::vector<int>{top});
  CHECK_THROWS_WITH_AS(geodesic_disc(sphere, sc, top, -1.0), doctest::Contains("geometry::geodesic_disc(): radius"),
                       InvalidArgument);
}

TEST_CASE("geometry: mirror_vertices twice gives the set back; what has no image is counted") {
  // A grid symmetric about x = 2 (and y = 1.5): a cap of it mirrored, twice.
  const TriMesh grid = make_irregular_grid(20, 15, 0.0, 1, 4, 3);
  const Eigen::Vector3d centre(2, 1.5, 0);
  std::vector<int> corner;
  for (int v = 0; v < grid.num_vertices(); ++v)
    if (grid.V(v, 0) < 1.1 && grid.V(v, 1) > 2.0) corner.push_back(v);
  REQUIRE(corner.size() > 10);
  for (int axis : {0, 1}) {
    CAPTURE(axis);
    const Eigen::Vector3d normal = Eigen::Vector3d::Unit(axis);
    const MirroredVertices once = mirror_vertices(grid.V, corner, centre, normal, 0.01);
    CHECK(once.unmatched.empty());
    REQUIRE(once.vertices.size() == corner.size());
    for (int v : once.vertices) CHECK(std::abs(grid.V(v, axis) - centre[axis]) > 0.45);  // on the other side
    const MirroredVertices twice = mirror_vertices(grid.V, once.vertices, centre, normal, 0.01);
    CHECK(twice.vertices == corner);
  }
  // Jittered (nearly symmetric): a coarse tolerance still finds every image, a fine one does
  // not, and each vertex lands in one list.
  const TriMesh jittered = make_irregular_grid(20, 15, 0.1, 7, 4, 3);
  const MirroredVertices coarse = mirror_vertices(jittered.V, corner, centre, Eigen::Vector3d::UnitX(), 0.1);
  const MirroredVertices fine = mirror_vertices(jittered.V, corner, centre, Eigen::Vector3d::UnitX(), 1e-6);
  CHECK(coarse.unmatched.empty());
  CHECK(fine.unmatched.size() > corner.size() / 2);
  CHECK(fine.vertices.size() + fine.unmatched.size() >= corner.size() - 1);
  // A mesh with nothing on the other side: every vertex unmatched.
  const MirroredVertices off =
      mirror_vertices(grid.V, corner, Eigen::Vector3d(-5, 0, 0), Eigen::Vector3d::UnitX(), 0.05);
  CHECK(off.vertices.empty());
  CHECK(off.unmatched == corner);
  CHECK_THROWS_WITH_AS(mirror_vertices(grid.V, corner, centre, Eigen::Vector3d::Zero(), 0.1),
                       doctest::Contains("geometry::mirror_vertices(): the plane's normal"), InvalidArgument);
  CHECK_THROWS_WITH_AS(mirror_vertices(grid.V, corner, centre, Eigen::Vector3d::UnitX(), 0.0),
                       doctest::Contains("geometry::mirror_vertices(): tolerance"), InvalidArgument);
  CHECK_THROWS_AS(mirror_vertices(grid.V, {-1}, centre, Eigen::Vector3d::UnitX(), 0.1), InvalidArgument);
}

TEST_CASE("geometry: near_region_border finds the candidates within k rings of the outside") {
  // A 30 x 4 strip of unit cells; the region is the columns x < 20; candidates: one vertex
  // per column, in the middle row.
  const int nx = 30, ny = 4;
  const TriMesh strip = make_plane_grid(nx, ny, nx, ny);
  const Connectivity conn(strip);
  std::vector<char> inside(static_cast<size_t>(strip.num_vertices()), 0);
  for (int v = 0; v < strip.num_vertices(); ++v) inside[static_cast<size_t>(v)] = strip.V(v, 0) < 19.5;
  std::vector<int> candidates;
  for (int i = 0; i <= nx; ++i) candidates.push_back(2 * (nx + 1) + i);
  for (int rings : {1, 2, 3}) {
    CAPTURE(rings);
    const std::vector<int> near = near_region_border(conn, inside, candidates, rings);
    // Column 19 is the region's last: column i is rings away from column 20 when 20 - i <= rings;
    // candidates outside (i >= 20) count too.
    for (int i = 0; i <= nx; ++i) CHECK(contains(near, 2 * (nx + 1) + i) == (i >= 20 - rings));
  }
  // No outside: nothing is near.
  const std::vector<char> all(static_cast<size_t>(strip.num_vertices()), 1);
  CHECK(near_region_border(conn, all, candidates, 5).empty());
  CHECK_THROWS_WITH_AS(near_region_border(conn, inside, candidates, 0),
                       doctest::Contains("geometry::near_region_border(): rings = 0"), InvalidArgument);
  CHECK_THROWS_AS(near_region_border(conn, inside, {strip.num_vertices()}, 1), InvalidArgument);
}
