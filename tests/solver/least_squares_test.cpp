#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <algorithm>
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

TEST_CASE("solver: least squares on thousands of unknowns (threaded assembly) equals Eigen's normal equations") {
  // Large enough that the normal matrices are assembled by several threads, with the fixed
  // unknowns given out of order: the reference is built by Eigen's own sparse products.
  std::mt19937 rng(11);
  const int n = 3000;
  const SparseMatrix A1 = random_sparse(4000, n, 0.002, rng), A2 = random_sparse(1500, n, 0.003, rng);
  const double w1 = 1.0, w2 = 7.5;
  std::vector<int> fixed;
  for (int i = n - 1; i >= 0; i -= 37) fixed.push_back(i);
  std::shuffle(fixed.begin(), fixed.end(), rng);
  LeastSquares ls(n);
  ls.add_block(A1, w1);
  ls.add_block(A2, w2);
  ls.set_fixed(fixed);
  ls.precompute();
  const DenseMatrix r1 = DenseMatrix::Random(4000, 2), r2 = DenseMatrix::Random(1500, 2);
  const DenseMatrix c = DenseMatrix::Random(static_cast<Eigen::Index>(fixed.size()), 2);
  const DenseMatrix x = ls.solve({r1, r2}, c);

  std::vector<char> is_fixed(n, 0);
  for (int i : fixed) is_fixed[static_cast<size_t>(i)] = 1;
  std::vector<Eigen::Triplet<double, int>> sf, sc;
  int nf = 0;
  for (int i = 0; i < n; ++i)
    if (!is_fixed[static_cast<size_t>(i)]) sf.emplace_back(i, nf++, 1.0);
  for (size_t j = 0; j < fixed.size(); ++j) sc.emplace_back(fixed[j], static_cast<int>(j), 1.0);
  SparseMatrix Sf(n, nf), Sc(n, static_cast<int>(fixed.size()));
  Sf.setFromTriplets(sf.begin(), sf.end());
  Sc.setFromTriplets(sc.begin(), sc.end());
  const SparseMatrix F1 = A1 * Sf, F2 = A2 * Sf;
  const SparseMatrix N =
      SparseMatrix(w1 * SparseMatrix(F1.transpose()) * F1) + SparseMatrix(w2 * SparseMatrix(F2.transpose()) * F2);
  const DenseMatrix rhs = w1 * (SparseMatrix(F1.transpose()) * (r1 - A1 * Sc * c)) +
                          w2 * (SparseMatrix(F2.transpose()) * (r2 - A2 * Sc * c));
  Eigen::SimplicialLDLT<SparseMatrix> ldlt(N);
  REQUIRE(ldlt.info() == Eigen::Success);
  const DenseMatrix xf = ldlt.solve(rhs);
  double worst = 0;
  for (int i = 0, j = 0; i < n; ++i)
    if (!is_fixed[static_cast<size_t>(i)]) worst = std::max(worst, (x.row(i) - xf.row(j++)).norm());
  CHECK(worst <= 1e-8 * (1 + xf.norm()));
  for (size_t j = 0; j < fixed.size(); ++j) CHECK(x.row(fixed[j]) == c.row(static_cast<int>(j)));
}

TEST_CASE("solver: a block in the metric Dᵀ D solves like the block D A with right-hand side D r") {
  std::mt19937 rng(5);
  const int n = 1200, m = 1500;
  const SparseMatrix A = random_sparse(m, n, 0.004, rng), L = random_sparse(900, n, 0.003, rng);
  const SparseMatrix D = random_sparse(2000, m, 0.002, rng);
  const SparseMatrix W = SparseMatrix(D.transpose()) * D;
  std::vector<int> fixed;
  for (int i = 7; i < n; i += 53) fixed.push_back(i);
  LeastSquares with_metric(n), plain(n);
  with_metric.add_block(L, 1.0, "L");
  with_metric.add_block(A, 0.3, "pairs", W);
  plain.add_block(L, 1.0, "L");
  plain.add_block(SparseMatrix(D * A), 0.3, "pairs");
  with_metric.set_fixed(fixed);
  plain.set_fixed(fixed);
  with_metric.precompute();
  plain.precompute();
  const DenseMatrix rl = DenseMatrix::Random(900, 3), r = DenseMatrix::Random(m, 3);
  const DenseMatrix c = DenseMatrix::Random(static_cast<Eigen::Index>(fixed.size()), 3);
  const DenseMatrix x = with_metric.solve({rl, r}, c), y = plain.solve({rl, DenseMatrix(D * r)}, c);
  CHECK((x - y).norm() <= 1e-8 * (1 + y.norm()));
  CHECK(with_metric.factor().report().nnz_L == plain.factor().report().nnz_L);
  CHECK_THROWS_WITH_AS(with_metric.add_block(A, 1.0, "bad", SparseMatrix(m, m + 1)), doctest::Contains("metric is"),
                       InvalidArgument);
  // The blocks are kept as added (the caller's copies above, the temporaries below taken),
  // and a rejected block leaves no trace.
  CHECK(with_metric.num_blocks() == 2);
  CHECK(with_metric.block_matrix(1).isApprox(A));
  CHECK(with_metric.block_metric(1).isApprox(W));
  CHECK(with_metric.block_metric(0).nonZeros() == 0);
  CHECK(plain.block_matrix(1).isApprox(SparseMatrix(D * A)));
  CHECK_THROWS_WITH_AS(plain.block_matrix(2), "solver::LeastSquares::block_matrix(): block 2 out of range [0, 2)",
                       InvalidArgument);
  CHECK_THROWS_AS(plain.block_metric(-1), InvalidArgument);
}

TEST_CASE("solver: least squares rejects bad input naming the function") {
  LeastSquares ls(10);
  CHECK_THROWS_WITH_AS(ls.add_block(SparseMatrix(4, 9), 1.0),
                       "solver::LeastSquares::add_block(): block is 4x9, expected 10 columns", InvalidArgument);
  CHECK_THROWS_AS(ls.add_block(SparseMatrix(4, 10), -1.0), InvalidArgument);
  CHECK_THROWS_WITH_AS(ls.set_fixed({2, 11}), "solver::LeastSquares::set_fixed(): index 11 out of range [0, 10)",
                       InvalidArgument);
  CHECK_THROWS_WITH_AS(ls.precompute(), "solver::LeastSquares::precompute(): no blocks added", InvalidArgument);
  SparseMatrix I(10, 10);
  I.setIdentity();
  ls.add_block(I, 1.0);
  ls.set_fixed({1, 2});
  ls.precompute();
  CHECK_THROWS_WITH_AS(ls.solve({DenseMatrix::Ones(9, 3)}, DenseMatrix::Ones(2, 3)),
                       "solver::LeastSquares::solve(): right-hand side of block 0 is 9x3, expected 10x3",
                       InvalidArgument);
  CHECK_THROWS_WITH_AS(ls.solve({DenseMatrix::Ones(10, 3)}, DenseMatrix::Ones(3, 3)),
                       "solver::LeastSquares::solve(): fixed values are 3x3, expected 2x3", InvalidArgument);
  // Unknowns no block touches are undetermined: a typed error, not garbage.
  LeastSquares under(4);
  SparseMatrix row(1, 4);
  row.insert(0, 0) = 1.0;
  under.add_block(row, 1.0);
  CHECK_THROWS_AS(under.precompute(), NotPositiveDefinite);
}

TEST_CASE("solver: refinement steps bring an ill-conditioned least-squares solve to the QR answer") {
  // A chain of 300 unknowns held at one end, rows of second differences plus a weak first
  // difference block: the normal matrix is so ill-conditioned that one back-substitution
  // carries errors near 1e-6 of the solution, and corrections from the rows' own residuals
  // (Björck's corrected semi-normal equations) take them to what a QR of the rows gives.
  const int n = 300;
  std::vector<Eigen::Triplet<double, int>> second, first;
  for (int i = 1; i + 1 < n; ++i) {
    second.emplace_back(i - 1, i - 1, 1.0), second.emplace_back(i - 1, i, -2.0), second.emplace_back(i - 1, i + 1, 1.0);
  }
  for (int i = 0; i + 1 < n; ++i) first.emplace_back(i, i, -1.0), first.emplace_back(i, i + 1, 1.0);
  SparseMatrix D2(n - 2, n), D1(n - 1, n);
  D2.setFromTriplets(second.begin(), second.end());
  D1.setFromTriplets(first.begin(), first.end());
  const double w1 = 1e-6;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  DenseMatrix r2(n - 2, 1), r1(n - 1, 1);
  for (auto& x : r2.reshaped()) x = u(rng);
  for (auto& x : r1.reshaped()) x = u(rng);
  LeastSquares ls(n);
  ls.add_block(D2, 1.0, "second differences");
  ls.add_block(D1, w1, "first differences");
  ls.set_fixed({0});
  ls.precompute();
  const DenseMatrix fixed = DenseMatrix::Constant(1, 1, 0.5);

  // Reference: QR of the stacked, weighted rows over the free unknowns.
  Eigen::MatrixXd A(2 * n - 3, n - 1);
  Eigen::VectorXd b(2 * n - 3);
  const Eigen::MatrixXd d2 = Eigen::MatrixXd(D2), d1 = Eigen::MatrixXd(D1);
  A << d2.rightCols(n - 1), std::sqrt(w1) * d1.rightCols(n - 1);
  b << r2.col(0) - d2.col(0) * 0.5, std::sqrt(w1) * (r1.col(0) - d1.col(0) * 0.5);
  const Eigen::VectorXd x_qr = A.colPivHouseholderQr().solve(b);

  auto error = [&](const DenseMatrix& x) { return (x.col(0).tail(n - 1) - x_qr).norm() / x_qr.norm(); };
  const double plain = error(ls.solve({r2, r1}, fixed));
  const double refined = error(ls.solve({r2, r1}, fixed, 2));
  MESSAGE("relative error: one solve " << plain << ", with two refinement steps " << refined);
  CHECK(plain > 1e-8);  // the case is ill-conditioned enough to show the difference
  CHECK(refined < 1e-9);
  CHECK(refined < 1e-2 * plain);
  // Zero steps is solve() itself.
  CHECK(ls.solve({r2, r1}, fixed, 0) == ls.solve({r2, r1}, fixed));
}
