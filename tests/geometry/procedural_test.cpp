// Procedural meshes are valid, outward oriented, and have the promised sizes and shapes.
#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "lapis/core/error.h"
#include "lapis/geometry/connectivity.h"
#include "lapis/geometry/procedural.h"

using namespace lapis::geometry;

namespace {
// Divergence theorem: positive for a closed, outward-oriented surface.
double signed_volume(const TriMesh& m) {
  double v = 0;
  for (int f = 0; f < m.num_faces(); ++f)
    v += Eigen::Vector3d(m.V.row(m.F(f, 0)))
             .dot(Eigen::Vector3d(m.V.row(m.F(f, 1))).cross(Eigen::Vector3d(m.V.row(m.F(f, 2)))));
  return v / 6;
}
}  // namespace

TEST_CASE("geometry: procedural meshes are valid with the promised sizes") {
  CHECK(make_plane_grid(3, 2).num_vertices() == 12);
  CHECK(make_plane_grid(3, 2).num_faces() == 12);
  CHECK(make_icosphere(3).num_vertices() == 10 * 64 + 2);
  CHECK(make_cylinder(12, 3).num_faces() == 72);
  for (const TriMesh& m :
       {make_plane_grid(5, 4), make_irregular_grid(8, 8), make_box_bar(2, 3, 10, 1, 1, 5), make_cylinder(16, 4),
        make_icosphere(2), make_torus(24, 12), make_double_torus(), loop_subdivide(make_cylinder(8, 2), 2)}) {
    const ValidationReport r = validate(m);
    CHECK_MESSAGE(r.ok(), r.summary());
  }
}

TEST_CASE("geometry: closed procedural meshes enclose their volume, outward") {
  CHECK(signed_volume(make_box_bar(2, 3, 10, 1, 2, 5)) == doctest::Approx(10.0));
  const double sphere = 4.0 / 3.0 * std::numbers::pi;
  CHECK(signed_volume(make_icosphere(5)) == doctest::Approx(sphere).epsilon(2e-3));
  const double torus = 2 * std::numbers::pi * std::numbers::pi * 1.0 * 0.4 * 0.4;
  CHECK(signed_volume(make_torus(128, 64)) == doctest::Approx(torus).epsilon(3e-3));
  CHECK(signed_volume(make_double_torus()) > 0);
}

TEST_CASE("geometry: Loop subdivision converges toward the limit without shrinking a plane") {
  const TriMesh plane = make_irregular_grid(4, 4);
  const TriMesh fine = loop_subdivide(plane, 2);
  CHECK(fine.num_faces() == 16 * plane.num_faces());
  CHECK(fine.V.col(2).cwiseAbs().maxCoeff() == 0.0);  // a planar mesh stays planar
  // The boundary rule keeps straight boundaries straight, and corners fixed.
  CHECK(fine.V.col(0).minCoeff() == doctest::Approx(0.0));
  CHECK(fine.V.col(0).maxCoeff() == doctest::Approx(1.0));
  // A subdivided icosahedron shrinks toward its limit surface (inside the unit sphere) but
  // stays round: all radii close to each other.
  const TriMesh ball = loop_subdivide(make_icosphere(0), 3);
  const Eigen::VectorXd radii = ball.V.rowwise().norm();
  CHECK(radii.maxCoeff() < 1.0);
  CHECK(radii.maxCoeff() - radii.minCoeff() < 0.02);
  CHECK_THROWS_AS(loop_subdivide(plane, 20), lapis::ResourceLimit);
  CHECK_THROWS_WITH_AS(make_cylinder(2, 1), "geometry::make_cylinder(): n_around = 2, expected at least 3",
                       lapis::InvalidArgument);
}
