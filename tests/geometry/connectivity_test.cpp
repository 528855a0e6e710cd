// Connectivity: edges, rings, boundary loops, Euler characteristic and genus.
#include <doctest/doctest.h>

#include <algorithm>
#include <set>

#include "lapis/core/error.h"
#include "lapis/geometry/connectivity.h"
#include "lapis/geometry/io.h"
#include "lapis/geometry/procedural.h"
#include "test_util.h"

using namespace lapis::geometry;

TEST_CASE("geometry: Euler characteristic and genus of sphere, torus and double torus") {
  const Connectivity sphere(make_icosphere(3));
  CHECK(euler_characteristic(sphere) == 2);
  CHECK(genus(sphere) == 0);
  const Connectivity torus(make_torus(20, 10));
  CHECK(euler_characteristic(torus) == 0);
  CHECK(genus(torus) == 1);
  const Connectivity two(make_double_torus());
  CHECK(euler_characteristic(two) == -2);
  CHECK(genus(two) == 2);
  CHECK(two.boundary_loops().empty());
  CHECK(connected_components(two).count == 1);
  // The real genus-2 meshes agree.
  for (const char* name : {"double-torus-example.off"}) {
    const auto path = test::external_asset(name);
    if (!std::filesystem::exists(path)) continue;
    Warnings w;
    CHECK(genus(Connectivity(read_mesh(path, &w))) == 2);
  }
}

TEST_CASE("geometry: boundary loops of a cylinder are two ordered cycles") {
  const int n = 12;
  const TriMesh cyl = make_cylinder(n, 3);
  const Connectivity conn(cyl);
  REQUIRE(conn.boundary_loops().size() == 2);
  for (const auto& loop : conn.boundary_loops()) {
    REQUIRE(loop.size() == n);
    // Consecutive loop vertices (cyclically) are joined by boundary edges, all at one height.
    for (size_t i = 0; i < loop.size(); ++i) {
      const int e = conn.find_edge(loop[i], loop[(i + 1) % loop.size()]);
      REQUIRE(e >= 0);
      CHECK(conn.is_boundary_edge(e));
      CHECK(cyl.V(loop[i], 2) == cyl.V(loop[0], 2));
    }
    // Surface on the left: the bottom loop turns clockwise seen from +z, the top one
    // counter-clockwise... as signed area of the xy projection tells.
    double area = 0;
    for (size_t i = 0; i < loop.size(); ++i) {
      const auto p = cyl.V.row(loop[i]), q = cyl.V.row(loop[(i + 1) % loop.size()]);
      area += p.x() * q.y() - p.y() * q.x();
    }
    CHECK((cyl.V(loop[0], 2) == 0.0 ? area > 0 : area < 0));
  }
  CHECK(euler_characteristic(conn) == 0);
  CHECK(genus(conn) == 0);
  for (int v = 0; v < cyl.num_vertices(); ++v)
    CHECK(conn.is_boundary_vertex(v) == (cyl.V(v, 2) == 0.0 || cyl.V(v, 2) == 1.0));
}

TEST_CASE("geometry: edges, faces and neighbours are consistent") {
  const TriMesh m = make_irregular_grid(6, 5);
  const Connectivity conn(m);
  CHECK(conn.num_edges() == 6 * 6 + 5 * 7 + 6 * 5);  // horizontal + vertical + diagonals
  for (int f = 0; f < m.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const auto [a, b] = conn.edges()[conn.face_edge(f, k)];
      CHECK(std::set<int>{a, b} == std::set<int>{m.F(f, k), m.F(f, (k + 1) % 3)});
      const int g = conn.face_neighbor(f, k);
      if (g >= 0)
        CHECK(conn.face_neighbor(g, [&] {
          for (int j = 0; j < 3; ++j)
            if (conn.face_edge(g, j) == conn.face_edge(f, k)) return j;
          return -1;
        }()) == f);
    }
  for (int v = 0; v < m.num_vertices(); ++v) {
    const auto n = conn.vertex_neighbors(v);
    CHECK(std::is_sorted(n.begin(), n.end()));
    for (size_t i = 0; i < n.size(); ++i) CHECK(conn.find_edge(v, n[i]) == conn.vertex_edges(v)[i]);
  }
  CHECK(conn.find_edge(0, m.num_vertices() - 1) == -1);
  CHECK_THROWS_WITH_AS(Connectivity(TriMesh{m.V.topRows(3), m.F}), doctest::Contains("geometry::Connectivity(): face"),
                       lapis::InvalidArgument);
}

TEST_CASE("geometry: ordered one-rings follow face orientation") {
  const TriMesh m = make_icosphere(1);
  const Connectivity conn(m);
  for (int v = 0; v < m.num_vertices(); ++v) {
    const std::vector<int> ring = conn.one_ring_ordered(v);
    REQUIRE(ring.size() == conn.vertex_neighbors(v).size());
    // Consecutive ring vertices with v form a face of the mesh in this very orientation.
    for (size_t i = 0; i < ring.size(); ++i) {
      const int a = ring[i], b = ring[(i + 1) % ring.size()];
      bool found = false;
      for (int f : conn.vertex_faces(v))
        for (int k = 0; k < 3; ++k) found |= m.F(f, k) == v && m.F(f, (k + 1) % 3) == a && m.F(f, (k + 2) % 3) == b;
      CHECK(found);
    }
  }
  // Boundary vertex of a grid corner region: the open fan starts and ends on the boundary.
  const TriMesh grid = make_plane_grid(3, 3);
  const Connectivity g(grid);
  const std::vector<int> ring = g.one_ring_ordered(1);  // bottom edge, middle
  CHECK(ring.front() == 2);
  CHECK(ring.back() == 0);
  // A bow tie vertex has no single ring.
  TriMesh bow;
  bow.V.resize(5, 3);
  bow.V << 0, 0, 0, 1, 0, 0, 1, 1, 0, -1, 0, 0, -1, -1, 0;
  bow.F.resize(2, 3);
  bow.F << 0, 1, 2, 0, 3, 4;
  CHECK_THROWS_WITH_AS(Connectivity(bow).one_ring_ordered(0), doctest::Contains("vertex 0 is non-manifold"),
                       lapis::InvalidArgument);
}

TEST_CASE("geometry: k-rings and connected components") {
  const TriMesh grid = make_plane_grid(10, 10);
  const Connectivity conn(grid);
  const int centre = 5 * 11 + 5;
  CHECK(k_ring(conn, {centre}, 0).size() == 1);
  CHECK(k_ring(conn, std::vector<int>{centre}, 1).size() == 7);  // valence 6 on this grid
  const auto two = k_ring(conn, std::vector<int>{centre}, 2);
  CHECK(two.front() == centre);
  CHECK(two.size() == 19);
  CHECK_THROWS_AS(k_ring(conn, std::vector<int>{-1}, 1), lapis::InvalidArgument);
  // Two tori side by side are two components.
  TriMesh a = make_torus(8, 6), b = make_torus(8, 6);
  TriMesh both;
  both.V.resize(a.num_vertices() * 2, 3);
  both.V << a.V, b.V;
  both.F.resize(a.num_faces() * 2, 3);
  both.F << a.F, (b.F.array() + a.num_vertices()).matrix();
  const Components c = connected_components(Connectivity(both));
  CHECK(c.count == 2);
  CHECK(c.face_component.front() == 0);
  CHECK(c.face_component.back() == 1);
  CHECK(genus(both) == 2);
  CHECK(euler_characteristic(make_icosphere(0)) == 2);
}
