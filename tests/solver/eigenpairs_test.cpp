#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "grid_matrices.h"
#include "lapis/solver/eigenpairs.h"

using namespace lapis;
using namespace lapis::solver;
using namespace lapis::solver::testing;

namespace {

// −(path graph Laplacian): λ_j = 2 − 2 cos(π j / n), j = 0 … n − 1 (Neumann ends).
SparseMatrix path_stiffness(int n) {
  std::vector<Eigen::Triplet<double, int>> t;
  for (int i = 0; i + 1 < n; ++i) {
    t.emplace_back(i, i + 1, -1.0);
    t.emplace_back(i + 1, i, -1.0);
    t.emplace_back(i, i, 1.0);
    t.emplace_back(i + 1, i + 1, 1.0);
  }
  SparseMatrix K(n, n);
  K.setFromTriplets(t.begin(), t.end());
  return K;
}

SparseMatrix identity(int n) {
  SparseMatrix I(n, n);
  I.setIdentity();
  return I;
}

// A positive diagonal "mass" with entries in [0.5, 2): breaks the grid's multiple eigenvalues.
SparseMatrix random_mass(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.5, 2.0);
  SparseMatrix M(n, n);
  for (int i = 0; i < n; ++i) M.insert(i, i) = u(rng);
  M.makeCompressed();
  return M;
}

double orthonormality_error(const Eigenpairs& e, const SparseMatrix& M) {
  const Eigen::MatrixXd G = e.vectors.transpose() * (M * e.vectors);
  return (G - Eigen::MatrixXd::Identity(G.rows(), G.cols())).cwiseAbs().maxCoeff();
}

}  // namespace

TEST_CASE("solver: eigenpairs of the path graph match the closed form, both backends") {
  const int n = 200, k = 8;
  const SparseMatrix K = path_stiffness(n), M = identity(n);
  for (Backend b : {Backend::Cholmod, Backend::Eigen}) {
    CAPTURE(std::string(to_string(b)));
    EigenOptions o;
    o.backend = b;
    const Eigenpairs e = smallest_eigenpairs(K, M, k, o);
    REQUIRE(e.values.size() == k);
    REQUIRE(e.vectors.rows() == n);
    for (int j = 0; j < k; ++j) CHECK(std::abs(e.values[j] - (2 - 2 * std::cos(M_PI * j / n))) < 1e-11);
    CHECK(orthonormality_error(e, M) < 1e-10);
    CHECK(e.report.max_residual < 1e-10);
  }
}

TEST_CASE("solver: shift-invert Lanczos matches the dense reference on a singular grid Laplacian") {
  const SparseMatrix K = SparseMatrix(-grid_laplacian_3d(7));  // 343 rows, λ₁ = 0
  const SparseMatrix M = random_mass(static_cast<int>(K.rows()), 3);
  const int k = 12;
  const Eigenpairs lanczos = smallest_eigenpairs(K, M, k);
  EigenOptions dense;
  dense.backend = Backend::Eigen;
  const Eigenpairs ref = smallest_eigenpairs(K, M, k, dense);
  CHECK(lanczos.report.shift < 0);
  CHECK(lanczos.report.solves > 0);
  CHECK(std::abs(lanczos.values[0]) < 1e-10);
  for (int j = 1; j < k; ++j) CHECK(std::abs(lanczos.values[j] - ref.values[j]) < 1e-8 * ref.values[j]);
  CHECK(orthonormality_error(lanczos, M) < 1e-10);
  CHECK(lanczos.report.max_residual < 1e-9);
  // Each eigenvector is the reference's up to sign (the random mass leaves no multiple values).
  for (int j = 0; j < k; ++j) {
    const double overlap = lanczos.vectors.col(j).dot(M * ref.vectors.col(j));
    CHECK(std::abs(std::abs(overlap) - 1) < 1e-7);
  }
}

TEST_CASE("solver: eigenpairs scale with the problem: K → sK gives sλ") {
  const SparseMatrix K = path_stiffness(120), M = random_mass(120, 5);
  const Eigenpairs a = smallest_eigenpairs(K, M, 6);
  const Eigenpairs b = smallest_eigenpairs(SparseMatrix(250.0 * K), M, 6);
  for (int j = 1; j < 6; ++j) CHECK(std::abs(b.values[j] - 250.0 * a.values[j]) < 1e-9 * b.values[j]);
}

TEST_CASE("solver: eigenpairs reject bad input with typed errors naming the cause") {
  const SparseMatrix K = path_stiffness(30), M = identity(30);
  CHECK_THROWS_WITH_AS(smallest_eigenpairs(K, M, 30), doctest::Contains("expected 1 <= k < 30"), InvalidArgument);
  CHECK_THROWS_WITH_AS(smallest_eigenpairs(K, M, 0), doctest::Contains("k = 0"), InvalidArgument);
  CHECK_THROWS_WITH_AS(smallest_eigenpairs(K, identity(29), 3), doctest::Contains("like K"), InvalidArgument);
  SparseMatrix bad = K;
  bad.coeffRef(3, 3) = std::nan("");
  CHECK_THROWS_AS(smallest_eigenpairs(bad, M, 3), InvalidArgument);
  EigenOptions above;  // σ above λ₁ = 0: K − σM is indefinite
  above.shift = 0.5;
  CHECK_THROWS_WITH_AS(smallest_eigenpairs(K, M, 3, above), doctest::Contains("not positive definite"),
                       NotPositiveDefinite);
}

TEST_CASE("solver: eigenpairs report no convergence with the count that converged") {
  const SparseMatrix K = SparseMatrix(-grid_laplacian_3d(8));
  const SparseMatrix M = random_mass(static_cast<int>(K.rows()), 9);
  EigenOptions starved;
  starved.basis_size = 12;
  starved.max_restarts = 1;
  try {
    smallest_eigenpairs(K, M, 10, starved);
    FAIL("expected NoConvergence");
  } catch (const NoConvergence& e) {
    CHECK(std::string(e.what()).find("converged") != std::string::npos);
    CHECK(e.converged() < 10);
  }
}
