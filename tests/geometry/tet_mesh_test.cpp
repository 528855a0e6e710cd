#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "lapis/core/error.h"
#include "lapis/geometry/procedural.h"
#include "lapis/geometry/tet_mesh.h"

using namespace lapis;
using namespace lapis::geometry;

namespace {

// The cube [0, 1]³ as five tetrahedra (one central, four corners), positively oriented.
TetMesh five_tet_cube() {
  TetMesh m;
  m.V.resize(8, 3);
  for (int i = 0; i < 8; ++i) m.V.row(i) << (i & 1), (i >> 1) & 1, (i >> 2) & 1;
  m.T.resize(5, 4);
  m.T << 0, 1, 2, 4, 3, 2, 1, 7, 5, 4, 7, 1, 6, 7, 4, 2, 1, 2, 4, 7;
  for (int t = 0; t < 5; ++t) {
    const Eigen::Vector3d a = m.V.row(m.T(t, 0)).transpose();
    if (tet_volume(a, m.V.row(m.T(t, 1)).transpose(), m.V.row(m.T(t, 2)).transpose(), m.V.row(m.T(t, 3)).transpose()) <
        0)
      std::swap(m.T(t, 2), m.T(t, 3));
  }
  return m;
}

double total_volume(const TetMesh& m) {
  double v = 0;
  for (int t = 0; t < m.num_tets(); ++t)
    v += tet_volume(m.V.row(m.T(t, 0)).transpose(), m.V.row(m.T(t, 1)).transpose(), m.V.row(m.T(t, 2)).transpose(),
                    m.V.row(m.T(t, 3)).transpose());
  return v;
}

}  // namespace

TEST_CASE("geometry: tet location finds the containing tet with coordinates that reproduce the point") {
  const TetMesh m = five_tet_cube();
  CHECK(std::abs(total_volume(m) - 1) < 1e-14);
  // The central tet (4) shares each of its faces with one corner tet.
  const std::vector<SharedFace> shared = shared_faces(m);
  CHECK(shared.size() == 4);
  for (const SharedFace& f : shared) CHECK((f.tets[0] == 4 || f.tets[1] == 4));
  const TetLocator locator(m);
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(0, 1);
  for (int k = 0; k < 200; ++k) {
    const Eigen::Vector3d p(u(rng), u(rng), u(rng));
    const TetLocation loc = locator.locate(p);
    REQUIRE(loc.tet >= 0);
    CHECK(loc.inside);
    CHECK(loc.barycentric.minCoeff() >= -1e-12);
    CHECK(std::abs(loc.barycentric.sum() - 1) < 1e-14);
    Eigen::Vector3d q = Eigen::Vector3d::Zero();
    for (int a = 0; a < 4; ++a) q += loc.barycentric[a] * m.V.row(m.T(loc.tet, a)).transpose();
    CHECK((q - p).norm() < 1e-14);
  }
  // Outside: bound to the nearest tet, flagged, coordinates still reproduce the point.
  const TetLocation far = locator.locate(Eigen::Vector3d(1.5, 0.5, 0.5));
  CHECK_FALSE(far.inside);
  CHECK(far.barycentric.minCoeff() < 0);
  Eigen::Vector3d q = Eigen::Vector3d::Zero();
  for (int a = 0; a < 4; ++a) q += far.barycentric[a] * m.V.row(m.T(far.tet, a)).transpose();
  CHECK((q - Eigen::Vector3d(1.5, 0.5, 0.5)).norm() < 1e-13);
  // The tet touching the face x = 1 nearest (1.5, 0.5, 0.5): its face contains (1, 0.5, 0.5).
  bool touches = false;
  for (int a = 0; a < 4; ++a) touches |= m.V(m.T(far.tet, a), 0) == 1;
  CHECK(touches);
}

TEST_CASE("geometry: the lattice enclosure holds every surface vertex, near the requested size") {
  for (int target : {60, 150}) {
    CAPTURE(target);
    const TriMesh torus = make_torus(48, 24, 1.0, 0.35);
    const TetMesh solid = lattice_enclosure(torus, target);
    require_valid_tets(solid, "test");
    CHECK(solid.num_vertices() > target / 2);
    CHECK(solid.num_vertices() < 2 * target);
    const TetLocator locator(solid);
    int outside = 0;
    for (int i = 0; i < torus.num_vertices(); ++i) outside += !locator.locate(torus.V.row(i).transpose()).inside;
    CHECK(outside == 0);
  }
}

TEST_CASE("geometry: the lattice enclosure is solid: a sphere's centre lies inside it") {
  const TriMesh sphere = make_icosphere(3, 1.0);
  const TetMesh solid = lattice_enclosure(sphere, 200);
  const TetLocator locator(solid);
  CHECK(locator.locate(Eigen::Vector3d::Zero()).inside);
  // Its volume is at least the sphere's, at most its bounding cube's plus a shell of cubes.
  CHECK(total_volume(solid) > 4.0 / 3 * M_PI * 0.95);
  CHECK(total_volume(solid) < 27);
}

TEST_CASE("geometry: bad tet meshes and lattice requests are typed errors") {
  TetMesh m = five_tet_cube();
  std::swap(m.T(0, 0), m.T(0, 1));
  CHECK_THROWS_WITH_AS(TetLocator{m}, doctest::Contains("tet 0 has no positive volume"), InvalidArgument);
  m = five_tet_cube();
  m.T(2, 3) = 8;
  CHECK_THROWS_WITH_AS(require_valid_tets(m, "ctx"), doctest::Contains("ctx: tet 2 has vertex 8"), InvalidArgument);
  CHECK_THROWS_WITH_AS(lattice_enclosure(make_icosphere(1), 4), doctest::Contains("expected >= 8"), InvalidArgument);
  const TetLocator ok(five_tet_cube());
  CHECK_THROWS_AS(ok.locate(Eigen::Vector3d(std::nan(""), 0, 0)), InvalidArgument);
}
