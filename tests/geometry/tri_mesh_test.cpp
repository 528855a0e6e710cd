// validate() finds each problem kind and names the offending indices.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "lapis/core/error.h"
#include "lapis/geometry/procedural.h"
#include "lapis/geometry/tri_mesh.h"
#include "test_util.h"

using namespace lapis::geometry;

TEST_CASE("geometry: validate accepts clean meshes") {
  CHECK(validate(test::tetrahedron()).ok());
  CHECK(validate(make_icosphere(2)).ok());
  CHECK(validate(make_plane_grid(4, 3)).ok());
  CHECK(validate(TriMesh{}).ok());
}

TEST_CASE("geometry: validate reports each problem with its indices") {
  TriMesh m = make_plane_grid(2, 2);  // 9 vertices, 8 faces
  m.V(4, 2) = std::numeric_limits<double>::quiet_NaN();
  m.F.conservativeResize(12, 3);
  m.F.row(8) << 0, 1, 9;     // out of range
  m.F.row(9) << 0, 0, 1;     // repeated index
  m.F.row(10) = m.F.row(0);  // duplicate of face 0, also misoriented against it
  m.F.row(11) << 0, 1, 2;    // collinear: zero area
  const ValidationReport r = validate(m);
  CHECK(r.out_of_range_faces == std::vector<int>{8});
  CHECK(r.non_finite_vertices == std::vector<int>{4});
  CHECK(r.degenerate_faces == std::vector<int>{9, 11});
  CHECK(r.duplicate_faces == std::vector<int>{10});
  CHECK(!r.misoriented_edges.empty());
  CHECK_THROWS_WITH_AS(
      require_valid(m),
      doctest::Contains("geometry::require_valid(): invalid mesh: 1 faces with out-of-range indices: 8"),
      lapis::InvalidArgument);
  CHECK(r.summary().find("2 degenerate faces: 9, 11") != std::string::npos);
}

TEST_CASE("geometry: validate finds non-manifold edges and vertices") {
  // Three triangles on one edge (0, 1).
  TriMesh fin;
  fin.V.resize(5, 3);
  fin.V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1;
  fin.F.resize(3, 3);
  fin.F << 0, 1, 2, 1, 0, 3, 0, 1, 4;
  const ValidationReport r = validate(fin);
  REQUIRE(r.non_manifold_edges.size() == 1);
  CHECK(r.non_manifold_edges[0] == std::array<int, 2>{0, 1});
  // Two triangles touching at vertex 0 only (a bow tie).
  TriMesh bow;
  bow.V.resize(5, 3);
  bow.V << 0, 0, 0, 1, 0, 0, 1, 1, 0, -1, 0, 0, -1, -1, 0;
  bow.F.resize(2, 3);
  bow.F << 0, 1, 2, 0, 3, 4;
  const ValidationReport b = validate(bow);
  CHECK(b.non_manifold_vertices == std::vector<int>{0});
  CHECK(b.non_manifold_edges.empty());
}
