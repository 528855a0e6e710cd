#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <random>

#include "grid_matrices.h"
#include "lapis/solver/least_squares.h"

using namespace lapis;
using namespace lapis::solver;

namespace {

SparseMatrix random_sparse(int m, int n, double density, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1), p(0, 1);
  std::vector<Eigen::Triplet<double, int>> t;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < n; ++j)
      if (p(rng) < density || i % n == j) t.emplace_back(i, j, u(rng));
  SparseMatrix A(m, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

}  // namespace

TEST_CASE("solver: least squares with hard constraints equals a dense reference") {
  std::mt19937 rng(3);
  const int n = 40;
  const SparseMatrix A1 = random_sparse(60, n, 0.1, rng), A2 = random_sparse(25, n, 0.2, rng);
  const double w1 = 1.0, w2 = 100.0;  // soft constraints weigh more, as ω² does
  const std::vector<int> fixed = {3, 17, 29, 38};
  LeastSquares ls(n);
  const int b1 = ls.add_block(A1, w1, "laplacian");
  const int b2 = ls.add_block(A2, w2, "soft positions");
  CHECK(b1 == 0);
  CHECK(b2 == 1);
  ls.set_fixed(fixed);
  ls.precompute();

  for (int frame = 0; frame < 3; ++frame) {
    const DenseMatrix r1 = DenseMatrix::Random(60, 3), r2 = DenseMatrix::Random(25, 3);
    const DenseMatrix c = DenseMatrix::Random(4, 3);
    const DenseMatrix x = ls.solve({r1, r2}, c);

    // Dense reference: minimize over the free unknowns with the fixed ones substituted.
    Eigen::MatrixXd M(85, n);
    M << std::sqrt(w1) * Eigen::MatrixXd(A1), std::sqrt(w2) * Eigen::MatrixXd(A2);
    Eigen::MatrixXd r(85, 3);
    r << std::sqrt(w1) * r1, std::sqrt(w2) * r2;
    std::vector<int> free;
    for (int i = 0; i < n; ++i)
      if (std::find(fixed.begin(), fixed.end(), i) == fixed.end()) free.push_back(i);
    Eigen::MatrixXd Mf(85, static_cast<int>(free.size())), Mc(85, 4);
    for (size_t j = 0; j < free.size(); ++j) Mf.col(static_cast<int>(j)) = M.col(free[j]);
    for (size_t j = 0; j < fixed.size(); ++j) Mc.col(static_cast<int>(j)) = M.col(fixed[j]);
    const Eigen::MatrixXd xf = Mf.colPivHouseholderQr().solve(r - Mc * c);
    for (size_t j = 0; j < free.size(); ++j)
      CHECK((x.row(free[j]) - xf.row(static_cast<int>(j))).norm() <= 1e-9 * (1 + xf.norm()));
    for (size_t j = 0; j < fixed.size(); ++j) CHECK(x.row(fixed[j]) == c.row(static_cast<int>(j)));
  }
}

TEST_CASE("solver: least squares rejects bad input naming the function") {
  LeastSquares ls(10);
  CHECK_THROWS_WITH_AS(ls.add_block(SparseMatrix(4, 9), 1.0),
                       "solver::LeastSquares::add_block(): block is 4x9, expected 10 columns",
                       InvalidArgument);
  CHECK_THROWS_AS(ls.add_block(SparseMatrix(4, 10), -1.0), InvalidArgument);
  CHECK_THROWS_WITH_AS(ls.set_fixed({2, 11}),
                       "solver::LeastSquares::set_fixed(): index 11 out of range [0, 10)", InvalidArgument);
  CHECK_THROWS_WITH_AS(ls.precompute(), "solver::LeastSquares::precompute(): no blocks added",
                       InvalidArgument);
  SparseMatrix I(10, 10);
  I.setIdentity();
  ls.add_block(I, 1.0);
  ls.set_fixed({1, 2});
  ls.precompute();
  CHECK_THROWS_WITH_AS(ls.solve({DenseMatrix::Ones(9, 3)}, DenseMatrix::Ones(2, 3)),
                       "solver::LeastSquares::solve(): right-hand side of block 0 is 9x3, expected 10x3",
                       InvalidArgument);
  CHECK_THROWS_WITH_AS(ls.solve({DenseMatrix::Ones(10, 3)}, DenseMatrix::Ones(3, 3)),
                       "solver::LeastSquares::solve(): fixed values are 3x3, expected 2x3",
                       InvalidArgument);
  // Unknowns no block touches are undetermined: a typed error, not garbage.
  LeastSquares under(4);
  SparseMatrix row(1, 4);
  row.insert(0, 0) = 1.0;
  under.add_block(row, 1.0);
  CHECK_THROWS_AS(under.precompute(), NotPositiveDefinite);
}
