// Mesh edits for merging: removing a band, bridging two boundaries, welding.
#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <numbers>
#include <random>

#include "lapis/core/error.h"
#include "lapis/geometry/connectivity.h"
#include "lapis/geometry/mesh_edit.h"
#include "lapis/geometry/procedural.h"

using namespace lapis::geometry;

TEST_CASE("geometry: cutting a band out of a cylinder and bridging it back") {
  const int n = 16;
  const TriMesh cyl = make_cylinder(n, 6, 1.0, 6.0);
  // Remove the middle ring of quads: two cylinders, four boundary loops.
  std::vector<int> band;
  for (int f = 0; f < cyl.num_faces(); ++f)
    if (f / (2 * n) == 3) band.push_back(f);
  std::vector<int> map;
  TriMesh cut = remove_faces(cyl, band, &map);
  CHECK(cut.num_faces() == cyl.num_faces() - 2 * n);
  CHECK(cut.num_vertices() == cyl.num_vertices());  // every vertex still used
  const Connectivity conn(cut);
  REQUIRE(conn.boundary_loops().size() == 4);
  CHECK(connected_components(conn).count == 2);
  // The loops at z = 3 and z = 4 face each other; bridging restores one open cylinder.
  std::vector<std::vector<int>> middle;
  for (const auto& loop : conn.boundary_loops())
    if (cut.V(loop[0], 2) == 3.0 || cut.V(loop[0], 2) == 4.0) middle.push_back(loop);
  REQUIRE(middle.size() == 2);
  const std::vector<int> b(middle[1].rbegin(), middle[1].rend());  // run the same way as middle[0]
  CHECK(bridge_polylines(cut, middle[0], b, true) == 2 * n);
  const ValidationReport r = validate(cut);
  CHECK_MESSAGE(r.ok(), r.summary());
  const Connectivity joined(cut);
  CHECK(joined.boundary_loops().size() == 2);
  CHECK(connected_components(joined).count == 1);
  CHECK_THROWS_WITH_AS(bridge_polylines(cut, {0}, {1, 2}, false),
                       "geometry::bridge_polylines(): polylines have 1 and 2 vertices, expected at least 2 each",
                       lapis::InvalidArgument);
}

TEST_CASE("geometry: bridging two open polylines of different lengths") {
  TriMesh m;
  m.V.resize(9, 3);
  m.V << 0, 0, 0, 1, 0, 0, 2, 0, 0, 3, 0, 0, 4, 0, 0,  // a: 5 points
      0, 1, 0, 1.3, 1, 0, 2.7, 1, 0, 4, 1, 0;          // b: 4 points
  const int added = bridge_polylines(m, {0, 1, 2, 3, 4}, {5, 6, 7, 8}, false);
  CHECK(added == 7);
  const ValidationReport r = validate(m);
  CHECK_MESSAGE(r.ok(), r.summary());
  for (int f = 0; f < m.num_faces(); ++f) {  // the strip lies to the left of a: normals +z
    const Eigen::Vector3d p = m.V.row(m.F(f, 0)), q = m.V.row(m.F(f, 1)), s = m.V.row(m.F(f, 2));
    CHECK((q - p).cross(s - p).z() > 0);
  }
}

TEST_CASE("geometry: welding restores a split grid") {
  // Two grids sharing an edge geometrically but not topologically.
  TriMesh left = make_plane_grid(3, 3), right = make_plane_grid(3, 3);
  right.V.col(0).array() += 1.0;
  TriMesh both;
  both.V.resize(32, 3);
  both.V << left.V, right.V;
  both.F.resize(36, 3);
  both.F << left.F, (right.F.array() + 16).matrix();
  CHECK(Connectivity(both).boundary_loops().size() == 2);
  const std::vector<int> map = weld_vertices(both, 1e-9);
  CHECK(both.num_vertices() == 28);
  CHECK(map[16] == map[3]);  // right's (0, 0) is left's (3, 0)
  CHECK(Connectivity(both).boundary_loops().size() == 1);
  CHECK(validate(both).ok());
  // Explicit pairs meet at their midpoint.
  TriMesh grid = make_plane_grid(2, 1);
  const std::vector<int> pairs_map = weld_vertex_pairs(grid, {{0, 3}});
  CHECK(grid.num_vertices() == 5);
  CHECK(grid.V(pairs_map[0], 1) == doctest::Approx(0.5));
  CHECK(pairs_map[0] == pairs_map[3]);
}

TEST_CASE("geometry: bridging two square loops makes the same triangles after any similarity") {
  // Two rings of 12 points round a square, one unit apart: every quad between them is a unit
  // square, both of its diagonals equally long. Rounding after a rotation makes one of them
  // shorter by an ulp; the triangulation must not follow it.
  TriMesh rings;
  rings.V.resize(24, 3);
  rings.F.resize(0, 3);
  std::vector<int> a, b;
  for (int k = 0; k < 12; ++k) {
    const int side = k / 3, step = k % 3;
    const double along = step - 1.5;  // -1.5 .. 0.5 along each side of a 4-wide square
    const Eigen::Vector2d corner[4] = {{-1.5, -1.5}, {1.5, -1.5}, {1.5, 1.5}, {-1.5, 1.5}};
    const Eigen::Vector2d dir[4] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
    const Eigen::Vector2d p = corner[side] + (along + 1.5) * dir[side];
    rings.V.row(k) << p.x(), p.y(), 0.0;
    rings.V.row(12 + k) << p.x(), p.y(), 1.0;
    a.push_back(k);
    b.push_back(12 + k);
  }
  TriMesh reference = rings;
  bridge_polylines(reference, a, b, true);
  REQUIRE(reference.F.rows() == 24);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 50; ++trial) {
    CAPTURE(trial);
    const Eigen::Matrix3d R =
        Eigen::Quaterniond(Eigen::Vector4d(u(rng), u(rng), u(rng), u(rng)).normalized()).toRotationMatrix();
    const double scale = std::exp(3 * u(rng));
    const Eigen::RowVector3d shift(100 * u(rng), 100 * u(rng), 100 * u(rng));
    TriMesh moved = rings;
    moved.V = ((scale * rings.V * R.transpose()).rowwise() + shift).eval();
    bridge_polylines(moved, a, b, true);
    CHECK(moved.F == reference.F);
  }
}

namespace {

// Edges of faces [first, end) whose two faces turn by more than kFoldedDihedralDeg.
int folded_edges_from(const TriMesh& m, int first) {
  const Connectivity conn(m);
  auto normal = [&](int f) {
    const Eigen::Vector3d p = m.V.row(m.F(f, 0)), q = m.V.row(m.F(f, 1)), s = m.V.row(m.F(f, 2));
    return Eigen::Vector3d((q - p).cross(s - p).normalized());
  };
  std::vector<char> seen(static_cast<size_t>(conn.num_edges()), 0);
  int folded = 0;
  for (int f = first; f < m.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int e = conn.face_edge(f, k);
      if (seen[e] || conn.edge_face_count(e) != 2) continue;
      seen[e] = 1;
      const auto [g, h] = conn.edge_faces(e);
      folded += normal(g).dot(normal(h)) < std::cos(kFoldedDihedralDeg * std::numbers::pi / 180);
    }
  return folded;
}

}  // namespace

TEST_CASE("geometry: bridging a jagged cut does not fold the strip against the surface beside it") {
  // A cylinder with a gap of one row, its lower loop dense and zig-zagging up and down by most
  // of the gap, as a cut through a scanned mesh leaves it; the upper loop coarse and shifted
  // half a step. Shortest diagonals alone fold triangles back over the lower rim's faces.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  for (int trial = 0; trial < 20; ++trial) {
    CAPTURE(trial);
    const int fine = 48, coarse = 20;
    TriMesh lower = make_cylinder(fine, 3, 1.0, 1.0), upper = make_cylinder(coarse, 3, 1.0, 1.0);
    upper.V.col(2).array() += 1.2;
    for (int k = 0; k < fine; ++k) {  // the top ring of `lower`
      const double jag = 0.16 * u(rng);
      lower.V(3 * fine + k, 2) += k % 2 ? jag : -jag;
    }
    for (int k = 0; k < coarse; ++k) {
      const double phi = 2 * std::numbers::pi * (k + 0.5 + 0.3 * (u(rng) - 0.5)) / coarse;
      upper.V.row(k) << std::cos(phi), std::sin(phi), 1.2;
    }
    TriMesh m;
    m.V.resize(lower.num_vertices() + upper.num_vertices(), 3);
    m.V << lower.V, upper.V;
    m.F.resize(lower.num_faces() + upper.num_faces(), 3);
    m.F << lower.F, (upper.F.array() + lower.num_vertices()).matrix();
    std::vector<int> a, b;
    for (int k = 0; k < fine; ++k) a.push_back(3 * fine + k);
    for (int k = 0; k < coarse; ++k) b.push_back(lower.num_vertices() + k);
    const int first = m.num_faces();
    bridge_polylines(m, a, b, true);
    CHECK(validate(m).ok());
    CHECK(folded_edges_from(m, first) == 0);
  }
}

namespace {

double total_area(const TriMesh& m) {
  double a = 0;
  for (int f = 0; f < m.num_faces(); ++f)
    a += 0.5 * (m.V.row(m.F(f, 1)) - m.V.row(m.F(f, 0))).cross(m.V.row(m.F(f, 2)) - m.V.row(m.F(f, 0))).norm();
  return a;
}

}  // namespace

TEST_CASE("geometry: splitting edges keeps the surface, its winding and every index") {
  const TriMesh grid = make_plane_grid(3, 3);
  const Connectivity conn(grid);
  // One, two and three split edges per face: every edge of the middle vertex's faces.
  std::vector<std::pair<int, int>> edges;
  const int mid = 5;  // an interior vertex of the 4×4 lattice
  for (int f : conn.vertex_faces(mid))
    for (int k = 0; k < 3; ++k) edges.emplace_back(grid.F(f, k), grid.F(f, (k + 1) % 3));
  TriMesh m = grid;
  const int added = split_edges(m, edges);
  CHECK(added == 12);  // six spokes and six rim edges of the hexagonal fan, each once
  CHECK(m.V.topRows(grid.num_vertices()) == grid.V);
  for (int i = 0; i < added; ++i) {  // each new vertex halves one listed edge
    const Eigen::RowVector3d p = m.V.row(grid.num_vertices() + i);
    CHECK(std::any_of(edges.begin(), edges.end(), [&](const auto& e) {
      return (p - 0.5 * (grid.V.row(e.first) + grid.V.row(e.second))).norm() < 1e-15;
    }));
  }
  CHECK(total_area(m) == doctest::Approx(total_area(grid)).epsilon(1e-12));
  CHECK(validate(m).ok());  // manifold and consistently wound
  const Connectivity after(m);
  CHECK(after.boundary_loops().size() == 1);
  for (int f = 0; f < m.num_faces(); ++f) {  // no normal flipped: the grid lies in z = 0, facing +z
    const Eigen::Vector3d n = (m.V.row(m.F(f, 1)) - m.V.row(m.F(f, 0))).cross(m.V.row(m.F(f, 2)) - m.V.row(m.F(f, 0)));
    CHECK(n.z() > 0);
  }
  // A pair that is not an edge is refused, and the mesh is left as it was.
  TriMesh same = grid;
  CHECK_THROWS_WITH_AS(split_edges(same, {{0, 15}}), doctest::Contains("(0, 15) is not an edge"),
                       lapis::InvalidArgument);
  CHECK(same.F == grid.F);
  CHECK(same.V == grid.V);
  CHECK_THROWS_AS(split_edges(same, {{0, 99}}), lapis::InvalidArgument);
}
