// Discrete operators: the properties that make them Laplacians.
#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <array>
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

TEST_CASE("geometry: mixed areas split obtuse triangles 1/2, 1/4, 1/4 and use Voronoi cells otherwise") {
  TriMesh obtuse;
  obtuse.V.resize(3, 3);
  obtuse.V << 0, 0, 0, 4, 0, 0, 2, 0.5, 0;  // obtuse at vertex 2, area 1
  obtuse.F.resize(1, 3);
  obtuse.F << 0, 1, 2;
  const Eigen::VectorXd mixed = vertex_areas(obtuse, MassType::Mixed);
  CHECK(mixed[2] == doctest::Approx(0.5));
  CHECK(mixed[0] == doctest::Approx(0.25));
  CHECK(mixed[1] == doctest::Approx(0.25));
  // Right isosceles triangle with legs 1 (area 1/2): the circumcentre is the hypotenuse
  // midpoint, so the right-angle corner's cell is 1/4 and the other two 1/8 each.
  TriMesh right = obtuse;
  right.V << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  const Eigen::VectorXd cells = vertex_areas(right, MassType::Voronoi);
  CHECK(cells[0] == doctest::Approx(0.25));
  CHECK(cells[1] == doctest::Approx(0.125));
  CHECK(cells[2] == doctest::Approx(0.125));
  const Eigen::VectorXd thirds = vertex_areas(right, MassType::Barycentric);
  CHECK(thirds[1] == doctest::Approx(0.5 / 3));
}

TEST_CASE("geometry: a needle or cap thinner than kDegenerateTriangleHeight has zero cotangents") {
  const Eigen::Vector3d a(0, 0, 0), b(2, 0, 0);
  using Cot = std::array<double, 3>;
  CHECK(triangle_cotangents(a, Eigen::Vector3d(0, 2, 0), b) == Cot{0, 1, 1});  // right angle at p0
  // A cap whose apex lies on the base up to rounding: |cross| ~1e-16, cotangents ~1e16 before.
  CHECK(triangle_cotangents(a, b, Eigen::Vector3d(1, 1e-16, 0)) == Cot{});
  // Heights just under and over 1e-6 of the longest edge (2): 1.9e-6 and 2.1e-6.
  CHECK(triangle_cotangents(a, b, Eigen::Vector3d(1, 1.9e-6, 0)) == Cot{});
  const Cot cap = triangle_cotangents(a, b, Eigen::Vector3d(1, 2.1e-6, 0));
  CHECK(cap[2] == doctest::Approx((1.0 - 2.1e-6 * 2.1e-6) / (-2 * 2.1e-6)).epsilon(1e-12));  // cot of ~180°
  CHECK(cap[0] == doctest::Approx(1 / 2.1e-6).epsilon(1e-12));
  // A NaN coordinate counts as degenerate: no NaN reaches a Laplacian from here.
  CHECK(triangle_cotangents(a, b, Eigen::Vector3d(std::nan(""), 1, 0)) == Cot{});
}

TEST_CASE("geometry: a collapsed face adds nothing to the cotan Laplacian and keeps it semi-definite") {
  TriMesh m = make_irregular_grid(9, 7);
  // Face 40's first corner moved onto its opposite edge, off it by 1e-13 of the edge: a cap
  // with cotangents ~1e13 unless dropped.
  const int f = 40, v = m.F(f, 0), p = m.F(f, 1), q = m.F(f, 2);
  const Eigen::RowVector3d along = m.V.row(q) - m.V.row(p);
  m.V.row(v) = 0.5 * (m.V.row(p) + m.V.row(q)) + 1e-13 * Eigen::RowVector3d(-along.y(), along.x(), 0);
  TriMesh without = m;
  without.F.row(f) = m.F.row(m.num_faces() - 1);
  without.F.conservativeResize(m.num_faces() - 1, 3);
  const Eigen::SparseMatrix<double> L = cotan_laplacian(m);
  CHECK((L - cotan_laplacian(without)).norm() <= 1e-12 * L.norm());
  CHECK(Eigen::Map<const Eigen::VectorXd>(L.valuePtr(), L.nonZeros()).cwiseAbs().maxCoeff() < 100);  // no 1e13
  const Eigen::VectorXd x = Eigen::VectorXd::Random(m.num_vertices());
  CHECK(x.dot(L * x) <= 0);
  CHECK(vertex_areas(m).sum() == doctest::Approx(vertex_areas(without).sum()).epsilon(1e-9));
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
