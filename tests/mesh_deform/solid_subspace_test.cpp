#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "lapis/geometry/procedural.h"
#include "lapis/mesh_deform/solid_subspace.h"
#include "lapis/solver/cholesky.h"

using namespace lapis;
using namespace lapis::mesh_deform;

namespace {

Eigen::Matrix3d random_matrix(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::Matrix3d G;
  for (int i = 0; i < 9; ++i) G(i / 3, i % 3) = u(rng);
  return G + 2 * Eigen::Matrix3d::Identity();
}

// Eq. 7 at u in tet t for the coefficients Z (one column per coordinate).
Eigen::Vector3d interpolate(const geometry::TetMesh& m, int t, const Eigen::Vector3d& u, const solver::DenseMatrix& Z) {
  const Eigen::Vector4d phi = geometry::tet_barycentric(m, t, u);
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (int a = 0; a < 4; ++a) {
    const int i = m.T(t, a);
    const Eigen::Matrix3d M = Z.block<3, 3>(4 * i + 1, 0).transpose();
    x += phi[a] * (Z.row(4 * i).transpose() + M * (u - m.V.row(i).transpose()));
  }
  return x;
}

}  // namespace

TEST_CASE("mesh_deform: subspace coordinates locate every vertex and reproduce affine maps exactly") {
  const geometry::TriMesh torus = geometry::make_torus(40, 20, 1.0, 0.35);
  const geometry::TetMesh tets = geometry::lattice_enclosure(torus, 120);
  const SubspaceEmbedding e = embed_in_subspace(tets, torus.V);
  CHECK(e.strays == 0);
  REQUIRE(e.C.rows() == torus.num_vertices());
  REQUIRE(e.C.cols() == 4 * tets.num_vertices());
  // Rows: φ (the columns 4a) sum to 1 over at most 4 corners, all ≥ 0 inside.
  const solver::SparseMatrix Ct = e.C.transpose();
  for (int j = 0; j < torus.num_vertices(); ++j) {
    double sum = 0;
    int corners = 0;
    for (solver::SparseMatrix::InnerIterator it(Ct, j); it; ++it)
      if (it.row() % 4 == 0) {
        sum += it.value();
        ++corners;
        CHECK(it.value() >= -1e-12);
      }
    CHECK(corners <= 4);
    CHECK(std::abs(sum - 1) < 1e-12);
  }
  const double size = (torus.V.colwise().maxCoeff() - torus.V.colwise().minCoeff()).norm();
  CHECK((e.C * rest_coefficients(tets) - solver::DenseMatrix(torus.V)).cwiseAbs().maxCoeff() < 1e-12 * size);
  std::mt19937 rng(7);
  const Eigen::Matrix3d G = random_matrix(rng);
  const Eigen::Vector3d t(0.3, -1.2, 2.0);
  const solver::DenseMatrix P = e.C * affine_coefficients(tets, G, t);
  for (int j = 0; j < torus.num_vertices(); ++j)
    CHECK((P.row(j).transpose() - (G * torus.V.row(j).transpose() + t)).norm() < 1e-12 * size * G.norm());
}

TEST_CASE("mesh_deform: the modified barycentric interpolation is continuous across tet faces") {
  const geometry::TetMesh tets = geometry::lattice_enclosure(geometry::make_icosphere(2), 80);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  solver::DenseMatrix Z = solver::DenseMatrix::NullaryExpr(4 * tets.num_vertices(), 3, [&]() { return u(rng); });
  // Every face shared by two tets: the two tets' interpolations agree at random face points.
  int shared = 0;
  std::uniform_real_distribution<double> w(0, 1);
  for (const geometry::SharedFace& face : geometry::shared_faces(tets)) {
    ++shared;
    const auto& f = face.corners;
    const double a = w(rng), b = w(rng) * (1 - a);
    const Eigen::Vector3d p = a * tets.V.row(f[0]).transpose() + b * tets.V.row(f[1]).transpose() +
                              (1 - a - b) * tets.V.row(f[2]).transpose();
    CHECK((interpolate(tets, face.tets[0], p, Z) - interpolate(tets, face.tets[1], p, Z)).norm() < 1e-12);
  }
  CHECK(shared > 100);
}

TEST_CASE("mesh_deform: the subspace regularisers vanish exactly on affine maps and only there") {
  const geometry::TetMesh tets = geometry::lattice_enclosure(geometry::make_icosphere(2), 60);
  const solver::SparseMatrix Bd = discontinuity_rows(tets), Bv = vibration_rows(tets);
  std::mt19937 rng(5);
  const solver::DenseMatrix Z = affine_coefficients(tets, random_matrix(rng), Eigen::Vector3d(1, 2, 3));
  CHECK((Bd * Z).cwiseAbs().maxCoeff() < 1e-12);
  CHECK((Bv * Z).cwiseAbs().maxCoeff() < 1e-12);
  // A non-affine Z costs something.
  solver::DenseMatrix bent = Z;
  bent(0, 0) += 0.1;
  CHECK((Bd * bent).norm() + (Bv * bent).norm() > 1e-3);
  // The null space of BᵀB is the 4 affine degrees of freedom per coordinate: pinning four
  // non-coplanar points (x_i of four tet vertices and nothing else) makes it definite.
  solver::SparseMatrix N = solver::SparseMatrix(Bd.transpose()) * Bd + solver::SparseMatrix(Bv.transpose()) * Bv;
  for (int c : {0, 1, 2, 3}) N.coeffRef(4 * tets.T(0, c), 4 * tets.T(0, c)) += 1;
  solver::Cholesky chol;
  CHECK_NOTHROW(chol.compute(N));
}
