// Discrete operators: the properties that make them Laplacians.
#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "lapis/core/error.h"
#include "lapis/geometry/connectivity.h"
#include "lapis/geometry/laplacian.h"
#include "lapis/geometry/normals.h"
#include "lapis/geometry/procedural.h"

using namespace lapis::geometry;

TEST_CASE("geometry: cotan Laplacian is symmetric with constants in its null space") {
  for (const TriMesh& m : {make_irregular_grid(9, 7), make_icosphere(2), make_double_torus(16, 8)}) {
    const Eigen::SparseMatrix<double> L = cotan_laplacian(m);
    const Eigen::SparseMatrix<double> Lt = L.transpose();
    CHECK((L - Lt).norm() < 1e-12 * L.norm());
    CHECK((L * Eigen::VectorXd::Ones(m.num_vertices())).norm() < 1e-12 * L.norm());
    // Negative semi-definite: x^T L x <= 0 for random x.
    const Eigen::VectorXd x = Eigen::VectorXd::Random(m.num_vertices());
    CHECK(x.dot(L * x) <= 0);
    // Diagonal negative, one entry per edge and vertex.
    CHECK(L.diagonal().maxCoeff() < 0);
    CHECK(L.nonZeros() == 2 * Connectivity(m).num_edges() + m.num_vertices());
  }
}

TEST_CASE("geometry: cotan Laplacian reproduces linear functions on a planar mesh") {
  const TriMesh m = make_irregular_grid(12, 10, 0.24);
  const Connectivity conn(m);
  const Eigen::SparseMatrix<double> L = cotan_laplacian(m);
  const Eigen::VectorXd f = 3.0 * m.V.col(0) - 2.0 * m.V.col(1) + Eigen::VectorXd::Constant(m.num_vertices(), 0.7);
  const Eigen::VectorXd Lf = L * f;
  int interior = 0;
  for (int v = 0; v < m.num_vertices(); ++v)
    if (!conn.is_boundary_vertex(v)) {
      CHECK(std::abs(Lf[v]) < 1e-12);
      ++interior;
    }
  CHECK(interior == 11 * 9);
  // The uniform Laplacian does not (irregular grid): the check above can fail.
  const Eigen::VectorXd Uf = uniform_laplacian(m) * f;
  double worst = 0;
  for (int v = 0; v < m.num_vertices(); ++v)
    if (!conn.is_boundary_vertex(v)) worst = std::max(worst, std::abs(Uf[v]));
  CHECK(worst > 1e-3);
}

TEST_CASE("geometry: on a fine sphere delta points along the normal with length 2/r per area") {
  const double r = 2.5;
  const TriMesh sphere = make_icosphere(4, r);
  const Eigen::MatrixX3d delta = laplacian_coordinates(sphere);
  const Eigen::VectorXd area = vertex_areas(sphere, MassType::Voronoi);
  const Vertices N = vertex_normals(sphere);
  double worst_length = 0, worst_angle = 0;
  for (int v = 0; v < sphere.num_vertices(); ++v) {
    const Eigen::Vector3d d = delta.row(v).transpose() / area[v];
    worst_length = std::max(worst_length, std::abs(d.norm() - 2 / r) * r / 2);
    worst_angle = std::max(worst_angle, 1 - (-d.normalized()).dot(N.row(v).transpose()));
  }
  CHECK(worst_length < 0.02);  // relative
  CHECK(worst_angle < 1e-4);   // delta points inward, against the outward normal
}

TEST_CASE("geometry: mass matrices sum to the surface area and mixed areas stay positive") {
  const TriMesh m = make_irregular_grid(10, 10, 0.24, 7, 2.0, 3.0);
  for (MassType t : {MassType::Barycentric, MassType::Voronoi}) {
    const Eigen::VectorXd a = vertex_areas(m, t);
    CHECK(a.sum() == doctest::Approx(6.0).epsilon(1e-12));
    CHECK(a.minCoeff() > 0);
    CHECK(mass_matrix(m, t).diagonal() == a);
  }
  CHECK(face_areas(m).sum() == doctest::Approx(6.0).epsilon(1e-12));
  // Normalized Laplacian is M^-1 L.
  const Eigen::SparseMatrix<double> N = normalized_cotan_laplacian(m), L = cotan_laplacian(m);
  const Eigen::VectorXd a = vertex_areas(m);
  CHECK((Eigen::SparseMatrix<double>(a.asDiagonal() * N) - L).norm() < 1e-12 * L.norm());
}

TEST_CASE("geometry: uniform Laplacian has edge ones and minus degree on the diagonal") {
  const TriMesh m = make_icosphere(1);
  const Connectivity conn(m);
  const Eigen::SparseMatrix<double> U = uniform_laplacian(m);
  for (int v = 0; v < m.num_vertices(); ++v) {
    CHECK(U.coeff(v, v) == -conn.degree(v));
    for (int w : conn.vertex_neighbors(v)) CHECK(U.coeff(v, w) == 1.0);
  }
}

TEST_CASE("geometry: face and vertex normals point outward on a sphere") {
  const TriMesh s = make_icosphere(3);
  const Vertices N = vertex_normals(s);
  for (int v = 0; v < s.num_vertices(); ++v) CHECK(N.row(v).dot(s.V.row(v)) > 0.999);
  const Vertices FN = face_normals(s);
  for (int f = 0; f < s.num_faces(); ++f) CHECK(FN.row(f).dot(s.V.row(s.F(f, 0))) > 0.98);
  CHECK_THROWS_WITH_AS(laplacian_coordinates(cotan_laplacian(s), make_icosphere(1).V),
                       doctest::Contains("geometry::laplacian_coordinates(): L is 642 x 642, expected 42 x 42"),
                       lapis::InvalidArgument);
}
