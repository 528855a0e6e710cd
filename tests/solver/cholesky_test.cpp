#include <doctest/doctest.h>

#include <omp.h>

#include <random>
#include <thread>

#include "grid_matrices.h"
#include "lapis/solver/cholesky.h"

using namespace lapis;
using namespace lapis::solver;
using namespace lapis::solver::testing;

namespace {

double relative_residual(const SparseMatrix& A, const DenseMatrix& X, const DenseMatrix& B) {
  return (A * X - B).norm() / B.norm();
}

DenseMatrix random_rhs(int n, int k, unsigned seed) {
  std::srand(seed);
  return DenseMatrix::Random(n, k);
}

}  // namespace

TEST_CASE("solver: cholesky residual on random SPD and grid systems, every backend") {
  const SparseMatrix grid = hair_normal_matrix(10, spread_nodes(1000, 25));
  const SparseMatrix random = random_spd(400, 0.02, 7);
  for (const SparseMatrix* A : {&grid, &random}) {
    const DenseMatrix B = random_rhs(static_cast<int>(A->rows()), 3, 1);
    for (auto options : {CholeskyOptions{Backend::Cholmod, FactorKind::Supernodal},
                         CholeskyOptions{Backend::Cholmod, FactorKind::Simplicial},
                         CholeskyOptions{Backend::Eigen, FactorKind::Simplicial}}) {
      CAPTURE(std::string(to_string(options.backend)));
      CAPTURE(std::string(to_string(options.kind)));
      Cholesky chol(options);
      chol.compute(*A);
      const DenseMatrix X = chol.solve(B);
      // The grid system has condition ~1e8 (ω² = 1e4 against a bi-Laplacian): the residual
      // still must be at round-off level.
      CHECK(relative_residual(*A, X, B) <= 1e-10);
      CHECK(chol.report().n == A->rows());
      CHECK(chol.report().nnz_L >= A->rows());
    }
  }
}

TEST_CASE("solver: cholmod and eigen backends agree") {
  const SparseMatrix A = hair_normal_matrix(12, spread_nodes(1728, 40));
  const DenseMatrix B = random_rhs(1728, 3, 2);
  const DenseMatrix Xc = solve_spd(A, B, {Backend::Cholmod, FactorKind::Supernodal});
  const DenseMatrix Xe = solve_spd(A, B, {Backend::Eigen, FactorKind::Simplicial});
  CHECK((Xc - Xe).norm() / Xe.norm() <= 1e-9);
}

TEST_CASE("solver: the parallel supernodal solve equals cholmod_solve for any threads and widths") {
  // N = 20: the top separator has ~800 columns, so its panels are split over the threads;
  // the random matrix gives many tiny supernodes.
  const SparseMatrix grid = hair_normal_matrix(20, spread_nodes(8000, 200));
  const SparseMatrix random = random_spd(3000, 0.002, 11);
  for (const SparseMatrix* A : {&grid, &random}) {
    const int n = static_cast<int>(A->rows());
    Cholesky reference({Backend::Cholmod, FactorKind::Supernodal, 1, /*cholmod_solve=*/true});
    reference.compute(*A);
    for (int threads : {1, 2, 3, 5}) {
      CAPTURE(threads);
      Cholesky chol({Backend::Cholmod, FactorKind::Supernodal, threads});
      chol.compute(*A);
      for (int width : {1, 3, 4, 7, 70}) {  // 70: wider than the kernels' 64-column sums
        CAPTURE(width);
        const DenseMatrix B = random_rhs(n, width, static_cast<unsigned>(threads * 100 + width));
        CHECK((chol.solve(B) - reference.solve(B)).norm() <= 1e-12 * reference.solve(B).norm());
      }
    }
  }
}

TEST_CASE("solver: cholesky stats name the ordering and count the factor") {
  Cholesky chol;
  chol.compute(hair_normal_matrix(10, spread_nodes(1000, 25)));
  CHECK(!chol.report().ordering.empty());
  CHECK(chol.report().ordering != "unknown");
  CHECK(chol.report().flops > 0);
  CHECK(chol.report().nnz_L > chol.report().nnz_A / 2);
}

TEST_CASE("solver: refactorize with the same pattern and new values") {
  SparseMatrix A = random_spd(300, 0.03, 3);
  Cholesky chol;
  chol.analyze(A);
  chol.factorize(A);
  const DenseMatrix B = random_rhs(300, 2, 3);
  for (int round = 0; round < 3; ++round) {
    A.coeffs() *= 1.5;
    for (int i = 0; i < 300; ++i) A.coeffRef(i, i) += 0.1 * round;
    chol.factorize(A);
    CHECK(relative_residual(A, chol.solve(B), B) <= 1e-10);
  }
  // A new pattern is re-analyzed, not misread.
  SparseMatrix C = random_spd(300, 0.05, 4);
  chol.factorize(C);
  CHECK(relative_residual(C, chol.solve(B), B) <= 1e-10);
}

TEST_CASE("solver: a matrix that is not positive definite throws naming the column") {
  SparseMatrix A = random_spd(50, 0.1, 5);
  A.coeffRef(17, 17) = -1e3;  // a negative pivot somewhere past the ordering's 17th step
  for (auto backend : {Backend::Cholmod, Backend::Eigen}) {
    CAPTURE(std::string(to_string(backend)));
    Cholesky chol({backend, FactorKind::Supernodal});
    REQUIRE_THROWS_AS(chol.compute(A), NotPositiveDefinite);
    CHECK(!chol.factorized());
    try {
      chol.compute(A);
    } catch (const NotPositiveDefinite& e) {
      CHECK(std::string(e.what()).find("solver::Cholesky::factorize(): matrix is not positive definite") == 0);
      CHECK(e.column() >= 0);
      CHECK(e.column() < 50);
    }
    CHECK_THROWS_WITH_AS(chol.solve(DenseMatrix::Ones(50, 1)),
                         "solver::Cholesky::solve(): no factorization (call factorize() first)", InvalidArgument);
  }
}

TEST_CASE("solver: wrong sizes and non-finite input throw with the function and the sizes") {
  Cholesky chol;
  CHECK_THROWS_WITH_AS(chol.compute(SparseMatrix(3, 4)),
                       "solver::Cholesky::analyze(): matrix is 3x4, expected a square matrix", InvalidArgument);
  CHECK_THROWS_WITH_AS(chol.compute(SparseMatrix(0, 0)), "solver::Cholesky::analyze(): matrix is empty (0x0)",
                       InvalidArgument);
  const SparseMatrix A = random_spd(20, 0.2, 6);
  chol.compute(A);
  CHECK_THROWS_WITH_AS(chol.solve(DenseMatrix::Ones(19, 3)),
                       "solver::Cholesky::solve(): right-hand side is 19x3, expected 20 rows", InvalidArgument);
  DenseMatrix nan_rhs = DenseMatrix::Ones(20, 1);
  nan_rhs(4, 0) = std::nan("");
  CHECK_THROWS_WITH_AS(chol.solve(nan_rhs),
                       "solver::Cholesky::solve(): right-hand side has a non-finite entry (NaN or Inf)",
                       InvalidArgument);
  SparseMatrix B = A;
  B.coeffRef(3, 3) = std::numeric_limits<double>::infinity();
  CHECK_THROWS_WITH_AS(chol.factorize(B), "solver::Cholesky::factorize(): matrix has a non-finite entry (NaN or Inf)",
                       InvalidArgument);
}

TEST_CASE("solver: independent objects factorize and solve on different threads") {
  const SparseMatrix A1 = hair_normal_matrix(9, spread_nodes(729, 20));
  const SparseMatrix A2 = random_spd(500, 0.02, 8);
  const DenseMatrix B1 = random_rhs(729, 3, 9), B2 = random_rhs(500, 3, 10);
  double r1 = 0, r2 = 0;
  std::thread t1([&] {
    for (int k = 0; k < 5; ++k) r1 = std::max(r1, relative_residual(A1, solve_spd(A1, B1), B1));
  });
  std::thread t2([&] {
    for (int k = 0; k < 5; ++k) r2 = std::max(r2, relative_residual(A2, solve_spd(A2, B2), B2));
  });
  t1.join();
  t2.join();
  CHECK(r1 <= 1e-10);
  CHECK(r2 <= 1e-10);
}

TEST_CASE("solver: a factorization leaves the caller's OpenMP nesting as it found it") {
  // CHOLMOD's own parallel regions run serial during the factorization (cholmod_factor.cpp);
  // the limit must not outlive it, on this thread or another.
  const SparseMatrix A = hair_normal_matrix(12, spread_nodes(1728, 40));
  const int levels = omp_get_max_active_levels();
  Cholesky chol;
  chol.compute(A);
  CHECK(omp_get_max_active_levels() == levels);
  int team = 0;
#pragma omp parallel num_threads(2)
  {
#pragma omp atomic
    ++team;
  }
  CHECK(team == 2);
  const DenseMatrix B = random_rhs(1728, 3, 12);
  CHECK(relative_residual(A, chol.solve(B), B) <= 1e-10);
}
