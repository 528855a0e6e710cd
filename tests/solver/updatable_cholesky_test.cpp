#include <doctest/doctest.h>

#include <algorithm>
#include <random>

#include "grid_matrices.h"
#include "lapis/solver/cholesky.h"
#include "lapis/solver/updatable_cholesky.h"

using namespace lapis;
using namespace lapis::solver;
using namespace lapis::solver::testing;

namespace {

double relative_difference(const DenseMatrix& X, const DenseMatrix& Y) { return (X - Y).norm() / Y.norm(); }

// A sparse n by r matrix with a few random entries per column, scaled so that an update
// is of the size of the matrix's own entries.
SparseMatrix random_columns(int n, int r, std::mt19937& rng, double scale) {
  std::uniform_int_distribution<int> row(0, n - 1), count(1, 3);
  std::uniform_real_distribution<double> value(-scale, scale);
  std::vector<Eigen::Triplet<double, int>> t;
  for (int j = 0; j < r; ++j) {
    const int c = count(rng);
    for (int k = 0; k < c; ++k) t.emplace_back(row(rng), j, value(rng));
  }
  SparseMatrix C(n, r);
  C.setFromTriplets(t.begin(), t.end());
  return C;
}

// The hair system on an N³ grid: DᵀD, and ω² = 10⁴ on 2.5% of the nodes.
struct HairSystem {
  int n;
  SparseMatrix DtD;
  Eigen::VectorXd weights;
  explicit HairSystem(int N) : n(N * N * N), DtD(hair_normal_matrix(N, {})), weights(Eigen::VectorXd::Zero(n)) {
    for (int i : spread_nodes(n, n / 40)) weights[i] = 1e4;
  }
};

}  // namespace

TEST_CASE("solver: updown matches refactor after 50 random mixed modifications") {
  const int N = 9, n = N * N * N;
  const SparseMatrix A0 = hair_normal_matrix(N, {});  // weights come through set_diagonal_weights
  const DenseMatrix B = DenseMatrix::Random(n, 3);
  for (ModifyMethod method : {ModifyMethod::UpdateDowndate, ModifyMethod::Refactorize, ModifyMethod::Auto}) {
    CAPTURE(std::string(to_string(method)));
    // DᵀD alone is singular (constants are in D's null space): start from a few constraints.
    SparseMatrix start = A0;
    for (int i : spread_nodes(n, 10)) start.coeffRef(i, i) += 1e4;
    UpdatableCholesky chol({Backend::Cholmod, method});
    chol.compute(start);
    std::mt19937 rng(42);
    std::uniform_int_distribution<int> kind(0, 2), node(0, n - 1), rank(1, 12);
    std::vector<SparseMatrix> applied;  // updates that may later be downdated
    int downdates = 0;
    for (int step = 0; step < 50; ++step) {
      const int k = kind(rng);
      if (k == 0 || (k == 1 && applied.empty())) {
        applied.push_back(random_columns(n, rank(rng), rng, 3.0));
        chol.update(applied.back());
      } else if (k == 1) {
        chol.downdate(applied.back());  // removes an earlier update exactly: stays SPD
        applied.pop_back();
        ++downdates;
      } else {
        std::vector<int> idx;
        std::vector<double> w;
        for (int j = rank(rng) * 4; j > 0; --j) {
          idx.push_back(node(rng));
          w.push_back(std::uniform_int_distribution<int>(0, 2)(rng) == 0 ? 0.0 : 1e4);
        }
        chol.set_diagonal_weights(idx, w);
      }
      if (method != ModifyMethod::Auto) CHECK(chol.last_report().method == method);
    }
    CHECK(downdates > 5);
    Cholesky fresh;
    fresh.compute(chol.matrix());
    CHECK(relative_difference(chol.solve(B), fresh.solve(B)) <= 1e-8);
    // And the tracked matrix really is A₀ + Σ modifications: cross-check with Eigen's LDLᵀ.
    CHECK(relative_difference(chol.solve(B), solve_spd(chol.matrix(), B, {Backend::Eigen})) <= 1e-8);
  }
}

TEST_CASE("solver: set_diagonal_weights equals a fresh factorization of the weighted matrix") {
  const int N = 10, n = N * N * N;
  const SparseMatrix base = hair_normal_matrix(N, {});
  SparseMatrix A = base;
  const std::vector<int> first = spread_nodes(n, 30, 0);
  for (int i : first) A.coeffRef(i, i) += 1e-6;  // keep A₀ definite; weights carry ω²
  UpdatableCholesky chol;
  chol.compute(A);
  chol.set_diagonal_weights(first, std::vector<double>(first.size(), 1e4));
  const std::vector<int> second = spread_nodes(n, 30, 7);
  std::vector<int> idx = second;
  std::vector<double> w(second.size(), 1e4);
  for (int i : first) {  // remove the first set, add the second: one update + one downdate
    idx.push_back(i);
    w.push_back(0.0);
  }
  const ModifyReport report = chol.set_diagonal_weights(idx, w);
  CHECK(report.rank == static_cast<int>(first.size() + second.size()));
  for (int i : second) A.coeffRef(i, i) += 1e4;
  CHECK(chol.diagonal_weight(second[3]) == 1e4);
  CHECK(chol.diagonal_weight(first[3]) == 0.0);
  const DenseMatrix B = DenseMatrix::Random(n, 3);
  CHECK(relative_difference(chol.solve(B), solve_spd(A, B)) <= 1e-8);
  CHECK((chol.matrix() - A).norm() <= 1e-9 * A.norm());
}

TEST_CASE("solver: a downdate that makes the matrix indefinite throws and keeps the previous system") {
  const SparseMatrix A = random_spd(200, 0.03, 11);
  const DenseMatrix B = DenseMatrix::Random(200, 2);
  for (ModifyMethod method : {ModifyMethod::UpdateDowndate, ModifyMethod::Refactorize}) {
    CAPTURE(std::string(to_string(method)));
    UpdatableCholesky chol({Backend::Cholmod, method});
    chol.compute(A);
    const DenseMatrix before = chol.solve(B);
    SparseMatrix C(200, 1);
    C.insert(57, 0) = 2.0 * std::sqrt(A.coeff(57, 57));  // removes 4× the diagonal entry
    try {
      chol.downdate(C);
      FAIL("downdate to an indefinite matrix did not throw");
    } catch (const NotPositiveDefinite& e) {
      CHECK(std::string(e.what()).find("solver::UpdatableCholesky::downdate()") == 0);
      CHECK(e.column() >= 0);
    }
    CHECK(relative_difference(chol.solve(B), before) <= 1e-10);
    CHECK((chol.matrix() - A).norm() == 0.0);
    // Still modifiable afterwards.
    chol.update(C);
    SparseMatrix A2 = A;
    A2.coeffRef(57, 57) += C.coeff(57, 0) * C.coeff(57, 0);
    CHECK(relative_difference(chol.solve(B), solve_spd(A2, B)) <= 1e-9);
  }
}

TEST_CASE("solver: the eigen backend refactorizes and agrees with cholmod updown") {
  const int N = 8, n = N * N * N;
  SparseMatrix A = hair_normal_matrix(N, spread_nodes(n, 12));
  UpdatableCholesky cholmod({Backend::Cholmod, ModifyMethod::UpdateDowndate});
  UpdatableCholesky eigen({Backend::Eigen, ModifyMethod::Auto});
  cholmod.compute(A);
  eigen.compute(A);
  const std::vector<int> idx = spread_nodes(n, 20, 3);
  const std::vector<double> w(idx.size(), 1e4);
  cholmod.set_diagonal_weights(idx, w);
  CHECK(eigen.set_diagonal_weights(idx, w).method == ModifyMethod::Refactorize);
  const DenseMatrix B = DenseMatrix::Random(n, 3);
  CHECK(relative_difference(cholmod.solve(B), eigen.solve(B)) <= 1e-9);
}

TEST_CASE("solver: the automatic choice reports its predictions and picks the cheaper one") {
  const int N = 14, n = N * N * N;
  UpdatableCholesky chol;
  chol.compute(hair_normal_matrix(N, spread_nodes(n, 60)));
  // One constraint: update/downdate touches one path of the elimination tree.
  const int one[] = {n / 2};
  const double w[] = {1e4};
  ModifyReport small = chol.set_diagonal_weights(one, w);
  CHECK(small.method == ModifyMethod::UpdateDowndate);
  CHECK(small.predicted_updown_ms < small.predicted_refactor_ms);
  CHECK(small.rank == 1);
  // Every node changes: n rank-1 modifications are predicted to cost hundreds of times one,
  // and the choice follows the predictions. (Which of the two is cheaper then depends on
  // the timings the model was calibrated with, and on a loaded machine one slow
  // factorization can make either side win.)
  std::vector<int> all(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) all[static_cast<size_t>(i)] = i;
  ModifyReport big = chol.set_diagonal_weights(all, std::vector<double>(all.size(), 5.0));
  CHECK(big.predicted_updown_ms > 100 * small.predicted_updown_ms);
  CHECK(big.method == (big.predicted_refactor_ms < big.predicted_updown_ms ? ModifyMethod::Refactorize
                                                                           : ModifyMethod::UpdateDowndate));
  CHECK(big.ms > 0);
}

TEST_CASE("solver: updatable cholesky rejects bad arguments naming the function") {
  UpdatableCholesky chol;
  CHECK_THROWS_WITH_AS(chol.update(SparseMatrix(5, 1)),
                       "solver::UpdatableCholesky::update(): C is 5x1, expected 0 rows", InvalidArgument);
  chol.compute(random_spd(30, 0.1, 12));
  CHECK_THROWS_WITH_AS(chol.downdate(SparseMatrix(29, 2)),
                       "solver::UpdatableCholesky::downdate(): C is 29x2, expected 30 rows", InvalidArgument);
  const int idx[] = {3, 30};
  const double w[] = {1.0, 1.0};
  CHECK_THROWS_WITH_AS(chol.set_diagonal_weights(idx, w),
                       "solver::UpdatableCholesky::set_diagonal_weights(): index 30 out of range [0, 30)",
                       InvalidArgument);
  const int idx2[] = {3};
  const double neg[] = {-1.0};
  CHECK_THROWS_AS(chol.set_diagonal_weights(idx2, neg), InvalidArgument);
  CHECK_THROWS_WITH_AS(chol.set_diagonal_weights(idx2, w),
                       "solver::UpdatableCholesky::set_diagonal_weights(): 1 indices but 2 weights", InvalidArgument);
}

TEST_CASE("solver: the parallel simplicial solve equals cholmod's supernodal solve for any threads and widths") {
  // Large enough for nested dissection to give subtrees worth splitting over threads.
  const int N = 14, n = N * N * N;
  const SparseMatrix A = hair_normal_matrix(N, spread_nodes(n, n / 40));
  Cholesky reference({Backend::Cholmod, FactorKind::Supernodal, 1, /*cholmod_solve=*/true});
  reference.compute(A);
  std::mt19937 rng(7);
  for (int threads : {1, 2, 3, 5}) {
    CAPTURE(threads);
    UpdatableCholesky chol({Backend::Cholmod, ModifyMethod::UpdateDowndate, threads});
    chol.compute(A);
    for (int width : {1, 3, 4, 7, 70}) {  // 70: more than one 64-column block
      CAPTURE(width);
      const DenseMatrix B = DenseMatrix::Random(n, width);
      CHECK(relative_difference(chol.solve(B), reference.solve(B)) <= 1e-12);
    }
    // An update with off-diagonal entries adds fill: the elimination tree and the column
    // runs change, and the solve must follow them.
    const SparseMatrix C = random_columns(n, 6, rng, 3.0);
    chol.update(C);
    Cholesky fresh;
    fresh.compute(chol.matrix());
    const DenseMatrix B = DenseMatrix::Random(n, 3);
    CHECK(relative_difference(chol.solve(B), fresh.solve(B)) <= 1e-10);
  }
}

TEST_CASE("solver: many diagonal weight changes agree with general updates and a fresh factor, any threads" *
          doctest::test_suite("slow")) {
  // N = 18: subtrees worth splitting over threads in the solve.
  const HairSystem sys(18);
  const DenseMatrix B = DenseMatrix::Random(sys.n, 3);
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> node(0, sys.n - 1);
  for (int threads : {1, 2, 3}) {
    CAPTURE(threads);
    UpdatableCholesky sweep({Backend::Cholmod, ModifyMethod::UpdateDowndate, threads});
    sweep.compute(sys.DtD, sys.weights);
    SparseMatrix A = sweep.matrix();
    // Twenty edits, each switching 70 random nodes on or off.
    for (int edit = 0; edit < 20; ++edit) {
      std::vector<int> idx;
      std::vector<double> w;
      for (int k = 0; k < 70; ++k) {
        idx.push_back(node(rng));
        w.push_back(sweep.diagonal_weight(idx.back()) > 0 ? 0.0 : 1e4);
      }
      sweep.set_diagonal_weights(idx, w);
      CHECK(sweep.last_report().method == ModifyMethod::UpdateDowndate);
    }
    // The same matrix through cholmod_updown (general columns) and through a fresh factor.
    UpdatableCholesky general({Backend::Cholmod, ModifyMethod::UpdateDowndate, threads});
    general.compute(sys.DtD, sys.weights);
    const SparseMatrix delta = sweep.matrix() - general.matrix();
    std::vector<Eigen::Triplet<double, int>> up, down;
    for (int k = 0; k < delta.outerSize(); ++k)
      for (SparseMatrix::InnerIterator it(delta, k); it; ++it)
        if (it.value() > 0)
          up.emplace_back(it.row(), static_cast<int>(up.size()), std::sqrt(it.value()));
        else if (it.value() < 0)
          down.emplace_back(it.row(), static_cast<int>(down.size()), std::sqrt(-it.value()));
    SparseMatrix U(sys.n, static_cast<int>(up.size())), D(sys.n, static_cast<int>(down.size()));
    U.setFromTriplets(up.begin(), up.end());
    D.setFromTriplets(down.begin(), down.end());
    general.update(U);
    general.downdate(D);
    CHECK(relative_difference(sweep.solve(B), general.solve(B)) <= 1e-9);
    CHECK(relative_difference(sweep.solve(B), solve_spd(sweep.matrix(), B)) <= 1e-9);
  }
}

TEST_CASE("solver: one-sweep diagonal changes equal cholmod_updown's update and downdate, any rank and threads") {
  // N = 20: top-separator columns long enough to be split over the threads. Ranks around
  // the 16 terms one sweep takes, signs mixed, every node once per change. The changes
  // accumulate on one pair of factors per thread count, so a later rank also checks that a
  // modified factor modifies correctly again.
  const HairSystem sys(20);
  const DenseMatrix B = DenseMatrix::Random(sys.n, 3);
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> node(0, sys.n - 1);
  for (int threads : {1, 2, 3}) {
    CAPTURE(threads);
    UpdatableCholesky sweep({Backend::Cholmod, ModifyMethod::UpdateDowndate, threads});
    UpdatableCholesky general({Backend::Cholmod, ModifyMethod::UpdateDowndate, threads});
    sweep.compute(sys.DtD, sys.weights);
    general.compute(sys.DtD, sys.weights);
    for (int rank : {1, 2, 15, 16, 17, 40}) {
      CAPTURE(rank);
      std::vector<int> idx;
      std::vector<double> w;
      std::vector<Eigen::Triplet<double, int>> up, down;
      while (static_cast<int>(idx.size()) < rank) {
        const int i = node(rng);
        if (std::find(idx.begin(), idx.end(), i) != idx.end()) continue;
        const double now = sweep.diagonal_weight(i), next = now > 0 ? 0.0 : 2.5e3 * (1 + idx.size() % 3);
        idx.push_back(i);
        w.push_back(next);
        if (next > now)
          up.emplace_back(i, static_cast<int>(up.size()), std::sqrt(next - now));
        else
          down.emplace_back(i, static_cast<int>(down.size()), std::sqrt(now - next));
      }
      sweep.set_diagonal_weights(idx, w);
      SparseMatrix U(sys.n, static_cast<int>(up.size())), D(sys.n, static_cast<int>(down.size()));
      U.setFromTriplets(up.begin(), up.end());
      D.setFromTriplets(down.begin(), down.end());
      if (U.cols() > 0) general.update(U);
      if (D.cols() > 0) general.downdate(D);
      CHECK(relative_difference(sweep.solve(B), general.solve(B)) <= 1e-11);
    }
    // And against a fresh factorization of the matrix the changes made.
    CHECK(relative_difference(sweep.solve(B), solve_spd(sweep.matrix(), B)) <= 1e-9);
  }
}

TEST_CASE("solver: weights whose removal makes the matrix indefinite throw and keep the previous system") {
  const int N = 18, n = N * N * N;
  SparseMatrix A0 = hair_normal_matrix(N, {});
  for (int i = 0; i < n; ++i) A0.coeffRef(i, i) -= 0.5;  // indefinite alone: DᵀD has a null space
  const Eigen::VectorXd weights = Eigen::VectorXd::Ones(n);
  const std::vector<int> nodes = spread_nodes(n, n / 2);
  for (int threads : {1, 2}) {
    CAPTURE(threads);
    UpdatableCholesky chol({Backend::Cholmod, ModifyMethod::UpdateDowndate, threads});
    chol.compute(A0, weights);
    const DenseMatrix B = DenseMatrix::Random(n, 2);
    const DenseMatrix before = chol.solve(B);
    CHECK_THROWS_AS(chol.set_diagonal_weights(nodes, std::vector<double>(nodes.size(), 0.0)), NotPositiveDefinite);
    CHECK(chol.diagonal_weight(nodes[0]) == 1.0);
    // The failed downdate is undone by the matching update: the previous system up to the
    // round-off of a modified factor (1e-8).
    CHECK(relative_difference(chol.solve(B), before) <= 1e-8);
    // And it goes on working.
    const int one[] = {nodes[0]};
    const double w[] = {3.0};
    chol.set_diagonal_weights(one, w);
    CHECK(relative_difference(chol.solve(B), solve_spd(chol.matrix(), B)) <= 1e-9);
  }
}

TEST_CASE("solver: diagonal weights that only grow or only shrink equal a fresh factorization") {
  // One side of the modification is empty then (no update or no downdate columns).
  const int N = 6, n = N * N * N;
  SparseMatrix A = hair_normal_matrix(N, {});
  for (int i = 0; i < n; ++i) A.coeffRef(i, i) += 1.0;  // well conditioned: checks see only the modification
  const std::vector<int> nodes = spread_nodes(n, 12, 3);
  const DenseMatrix B = DenseMatrix::Random(n, 3);
  for (ModifyMethod method : {ModifyMethod::UpdateDowndate, ModifyMethod::Refactorize}) {
    CAPTURE(std::string(to_string(method)));
    UpdatableCholesky chol({Backend::Cholmod, method});
    chol.compute(A);
    chol.set_diagonal_weights(nodes, std::vector<double>(nodes.size(), 1e4));  // only grows
    SparseMatrix weighted = A;
    for (int i : nodes) weighted.coeffRef(i, i) += 1e4;
    CHECK(relative_difference(chol.solve(B), solve_spd(weighted, B)) <= 1e-8);
    chol.set_diagonal_weights(nodes, std::vector<double>(nodes.size(), 0.0));  // only shrinks
    CHECK(relative_difference(chol.solve(B), solve_spd(A, B)) <= 1e-8);
  }
}
