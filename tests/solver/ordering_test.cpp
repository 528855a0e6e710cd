#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <memory>
#include <random>
#include <string>
#include <thread>

#include "grid_matrices.h"
#include "lapis/solver/blas_threads.h"
#include "lapis/solver/cholesky.h"
#include "lapis/solver/least_squares.h"
#include "lapis/solver/ordering.h"

using namespace lapis;
using namespace lapis::solver;

namespace {

// 5-point Laplacian of an N×N grid, and its edges: the skeleton.
SparseMatrix grid_laplacian_2d(int N, SparseMatrix* edges = nullptr) {
  std::vector<Eigen::Triplet<double, int>> t, e;
  auto id = [N](int x, int y) { return y * N + x; };
  for (int y = 0; y < N; ++y)
    for (int x = 0; x < N; ++x) {
      int degree = 0;
      for (auto [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
        if (x + dx < 0 || y + dy < 0 || x + dx >= N || y + dy >= N) continue;
        t.emplace_back(id(x, y), id(x + dx, y + dy), 1.0);
        e.emplace_back(id(x, y), id(x + dx, y + dy), 1.0);
        ++degree;
      }
      t.emplace_back(id(x, y), id(x, y), -degree);
    }
  SparseMatrix L(N * N, N * N), E(N * N, N * N);
  L.setFromTriplets(t.begin(), t.end());
  E.setFromTriplets(e.begin(), e.end());
  if (edges) *edges = E;
  return L;
}

// (L²)ᵀ L² + I: couples nodes four grid steps apart, like the implicit Laplacian's Eq. 2.8
// matrix couples vertices four rings apart.
SparseMatrix wide_stencil_matrix(const SparseMatrix& L) {
  const SparseMatrix L2 = L * L;
  SparseMatrix A = SparseMatrix(L2.transpose()) * L2;
  SparseMatrix I(A.rows(), A.cols());
  I.setIdentity();
  A += I;
  A.makeCompressed();
  return A;
}

bool is_permutation_of_n(const std::vector<int>& p, int n) {
  std::vector<int> s = p;
  std::sort(s.begin(), s.end());
  for (int k = 0; k < n; ++k)
    if (s.size() != static_cast<size_t>(n) || s[static_cast<size_t>(k)] != k) return false;
  return true;
}

}  // namespace

TEST_CASE("solver: skeleton nested dissection orders a wide stencil about as well as CHOLMOD and solves the same") {
  SparseMatrix edges;
  const SparseMatrix A = wide_stencil_matrix(grid_laplacian_2d(70, &edges));
  const int n = static_cast<int>(A.rows());
  const std::vector<int> perm = skeleton_nested_dissection(A, edges, {.leaf_size = 200});
  REQUIRE(is_permutation_of_n(perm, n));

  Cholesky given, own;
  given.analyze(A, perm);
  given.factorize(A);
  own.compute(A);
  CHECK(given.report().ordering == "given");
  CAPTURE(given.report().nnz_L);
  CAPTURE(own.report().nnz_L);
  // Within 25% of CHOLMOD's best (AMD or METIS on A's own, 12× denser, graph).
  CHECK(given.report().nnz_L <= 1.25 * own.report().nnz_L);
  std::srand(5);
  const DenseMatrix B = DenseMatrix::Random(n, 3);
  const DenseMatrix X = given.solve(B), Y = own.solve(B);
  CHECK((X - Y).norm() / Y.norm() <= 1e-10);
  CHECK((A * X - B).norm() / B.norm() <= 1e-10);
}

// A shared gradient's anchors (thesis §3.5) couple a few unknowns to a whole region. Dissected
// with the rest they land on both sides of a separator, and the region joins it.
TEST_CASE("solver: skeleton nested dissection numbers dense unknowns last and keeps the factor small") {
  SparseMatrix edges;
  SparseMatrix A = wide_stencil_matrix(grid_laplacian_2d(70, &edges));
  const int n = static_cast<int>(A.rows());
  // 32 anchors spread over the grid, each coupled to the middle half of it.
  std::vector<int> anchors;
  for (int k = 0; k < 32; ++k) anchors.push_back((k * 151 + 7) % n);
  std::vector<Eigen::Triplet<double, int>> t;
  for (int a : anchors)
    for (int v = n / 4; v < 3 * n / 4; ++v)
      if (v != a)
        t.emplace_back(std::max(a, v), std::min(a, v), 1e-3), t.emplace_back(std::min(a, v), std::max(a, v), 1e-3);
  SparseMatrix C(n, n);
  C.setFromTriplets(t.begin(), t.end());
  A += C;
  for (int a : anchors) A.coeffRef(a, a) += 10.0;  // still diagonally dominant: positive definite
  A.makeCompressed();
  const std::vector<int> perm = skeleton_nested_dissection(A, edges, {.leaf_size = 200});
  REQUIRE(is_permutation_of_n(perm, n));
  std::vector<int> tail(perm.end() - 32, perm.end()), sorted = anchors;
  std::sort(tail.begin(), tail.end());
  std::sort(sorted.begin(), sorted.end());
  CHECK(tail == sorted);
  Cholesky given, own;
  given.analyze(A, perm);
  given.factorize(A);
  own.compute(A);
  CAPTURE(given.report().nnz_L);
  CAPTURE(own.report().nnz_L);
  CHECK(given.report().nnz_L <= 1.25 * own.report().nnz_L);
  const DenseMatrix B = DenseMatrix::Ones(n, 1);
  CHECK((A * given.solve(B) - B).norm() / B.norm() <= 1e-10);
}

TEST_CASE("solver: A's lower triangle alone orders, factorizes and solves as the whole of A") {
  // What LeastSquares now hands over: its normal matrix without the upper triangle.
  SparseMatrix edges;
  const SparseMatrix A = wide_stencil_matrix(grid_laplacian_2d(40, &edges));
  const SparseMatrix lower = A.triangularView<Eigen::Lower>();
  REQUIRE(lower.nonZeros() < A.nonZeros());
  const std::vector<int> perm = skeleton_nested_dissection(A, edges, {.leaf_size = 150});
  CHECK(skeleton_nested_dissection(lower, edges, {.leaf_size = 150}) == perm);
  std::srand(9);
  const DenseMatrix B = DenseMatrix::Random(A.rows(), 2);
  for (auto options : {CholeskyOptions{Backend::Cholmod, FactorKind::Supernodal},
                       CholeskyOptions{Backend::Cholmod, FactorKind::Simplicial},
                       CholeskyOptions{Backend::Eigen, FactorKind::Simplicial}}) {
    CAPTURE(std::string(to_string(options.backend)));
    Cholesky whole(options), half(options);
    whole.analyze(A, perm);
    whole.factorize(A);
    half.analyze(lower, perm);
    half.factorize(lower);
    CHECK(half.report().nnz_L == whole.report().nnz_L);
    CHECK((half.solve(B) - whole.solve(B)).norm() <= 1e-12 * whole.solve(B).norm());
  }
}

TEST_CASE("solver: orderings made on two threads at once equal those made one at a time") {
  // METIS keeps its random state in process-wide statics (cholmod_context.h): without the
  // solver's lock, a dissection and a CHOLMOD-chosen METIS ordering running together came
  // out different from run to run (mesh_deform's two systems at 200K vertices).
  SparseMatrix edges;
  const SparseMatrix wide = wide_stencil_matrix(grid_laplacian_2d(50, &edges));
  // A 3D grid: AMD's fill is poor there, so CHOLMOD tries METIS too and keeps it.
  SparseMatrix cube = -testing::grid_laplacian_3d(24);
  for (int i = 0; i < cube.rows(); ++i) cube.coeffRef(i, i) += 0.1;
  const auto dissect = [&] { return skeleton_nested_dissection(wide, edges, {.leaf_size = 100}); };
  const auto chosen = [&] {
    Cholesky chol;
    chol.analyze(cube);
    return std::make_pair(std::string(chol.report().ordering), chol.report().nnz_L);
  };
  const std::vector<int> alone = dissect();
  const auto chosen_alone = chosen();
  REQUIRE(chosen_alone.first == "METIS");  // CHOLMOD tried METIS after AMD, and kept it
  // Dissections one after another for as long as the other thread orders (three times), so
  // the two overlap whatever the machine's speed.
  std::atomic<bool> done{false};
  std::vector<std::pair<std::string, std::int64_t>> chosen_together;
  std::thread other([&] {
    for (int k = 0; k < 3; ++k) chosen_together.push_back(chosen());
    done = true;
  });
  int dissections = 0, differing = 0;
  while (!done || dissections == 0) {
    differing += dissect() != alone;
    ++dissections;
  }
  other.join();
  CAPTURE(dissections);
  CHECK(differing == 0);
  for (const auto& c : chosen_together) CHECK(c == chosen_alone);
}

TEST_CASE("solver: skeleton nested dissection of a disconnected skeleton, of tiny and of empty-skeleton matrices") {
  // Two grids side by side with no edge between them, one matrix.
  SparseMatrix e1;
  const SparseMatrix A1 = wide_stencil_matrix(grid_laplacian_2d(30, &e1));
  const int m = static_cast<int>(A1.rows());
  std::vector<Eigen::Triplet<double, int>> ta, te;
  for (int k = 0; k < A1.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(A1, k); it; ++it)
      ta.emplace_back(it.row(), it.col(), it.value()), ta.emplace_back(m + it.row(), m + it.col(), it.value());
  for (int k = 0; k < e1.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(e1, k); it; ++it)
      te.emplace_back(it.row(), it.col(), 1.0), te.emplace_back(m + it.row(), m + it.col(), 1.0);
  SparseMatrix A(2 * m, 2 * m), E(2 * m, 2 * m);
  A.setFromTriplets(ta.begin(), ta.end());
  E.setFromTriplets(te.begin(), te.end());
  const std::vector<int> perm = skeleton_nested_dissection(A, E, {.leaf_size = 50});
  REQUIRE(is_permutation_of_n(perm, 2 * m));
  Cholesky c;
  c.analyze(A, perm);
  c.factorize(A);
  std::srand(6);
  const DenseMatrix B = DenseMatrix::Random(2 * m, 2);
  CHECK((A * c.solve(B) - B).norm() / B.norm() <= 1e-10);

  // A skeleton with no edges: nothing to dissect, CAMD orders everything.
  const SparseMatrix none(2 * m, 2 * m);
  CHECK(is_permutation_of_n(skeleton_nested_dissection(A, none), 2 * m));
  // Smaller than a leaf.
  SparseMatrix tiny(1, 1);
  tiny.insert(0, 0) = 2.0;
  CHECK(skeleton_nested_dissection(tiny, tiny) == std::vector<int>{0});
}

TEST_CASE("solver: given orderings and skeletons are checked") {
  SparseMatrix edges;
  const SparseMatrix A = wide_stencil_matrix(grid_laplacian_2d(6, &edges));
  const int n = static_cast<int>(A.rows());
  Cholesky c;
  std::vector<int> perm(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k) perm[static_cast<size_t>(k)] = k;
  std::vector<int> repeated = perm, outside = perm, shorter = perm;
  repeated[3] = 2;
  outside[0] = n;
  shorter.pop_back();
  auto message = [&](const std::vector<int>& p) {
    try {
      c.analyze(A, p);
    } catch (const InvalidArgument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK(message(repeated).find("solver::Cholesky::analyze(): ordering is not a permutation") == 0);
  CHECK(message(repeated).find("2 repeated") != std::string::npos);
  CHECK(message(outside).find("out of range") != std::string::npos);
  CHECK(message(shorter).find(std::to_string(n - 1) + " entries, expected " + std::to_string(n)) != std::string::npos);
  CHECK(message(perm) == "no error");

  SparseMatrix small(n - 1, n - 1);
  CHECK_THROWS_WITH_AS(skeleton_nested_dissection(A, small),
                       doctest::Contains("skeleton is 35 by 35, the matrix 36 by 36"), InvalidArgument);
  LeastSquares ls(n);
  CHECK_THROWS_WITH_AS(ls.set_ordering_skeleton(small),
                       doctest::Contains("set_ordering_skeleton(): skeleton is 35x35, expected 36x36"),
                       InvalidArgument);
}

TEST_CASE("solver: least squares ordered on a skeleton solves as CHOLMOD's ordering does") {
  SparseMatrix edges;
  const SparseMatrix L = grid_laplacian_2d(40, &edges);
  const SparseMatrix L2 = L * L;  // rows reaching two steps: the normal matrix reaches four
  const int n = static_cast<int>(L.rows());
  std::vector<int> fixed;
  for (int k = 0; k < 40; ++k) fixed.push_back(k);  // one side of the grid held
  std::srand(8);
  const DenseMatrix r = DenseMatrix::Random(n, 3), c = DenseMatrix::Random(40, 3);
  DenseMatrix X[2];
  for (int with_skeleton = 0; with_skeleton < 2; ++with_skeleton) {
    LeastSquares ls(n);
    ls.add_block(L2, 1.0, "bi-Laplacian");
    ls.add_block(L, 0.5, "Laplacian");
    ls.set_fixed(fixed);
    if (with_skeleton) ls.set_ordering_skeleton(edges);
    ls.precompute();
    CHECK((ls.factor().report().ordering == "given") == (with_skeleton == 1));
    X[with_skeleton] = ls.solve({r, DenseMatrix()}, c);
  }
  // Another elimination order rounds differently, and a bi-Laplacian held on one side is
  // ill-conditioned: 1e-8 (the brief's bar for "equals a fresh factorization"), not round-off.
  CHECK((X[1] - X[0]).norm() / X[0].norm() <= 1e-8);

  // The Eigen reference backend takes the skeleton and orders by its own AMD.
  LeastSquares reference(n, CholeskyOptions{Backend::Eigen, FactorKind::Simplicial});
  reference.add_block(L2, 1.0, "bi-Laplacian");
  reference.add_block(L, 0.5, "Laplacian");
  reference.set_fixed(fixed);
  reference.set_ordering_skeleton(edges);
  reference.precompute();
  CHECK(reference.factor().report().ordering == "AMD (Eigen)");
  CHECK((reference.solve({r, DenseMatrix()}, c) - X[1]).norm() / X[1].norm() <= 1e-8);
}

TEST_CASE("solver: without OpenBLAS a BLAS thread guard does nothing" * doctest::skip(ScopedBlasThreads::available())) {
  CHECK(ScopedBlasThreads::current() == 0);
  ScopedBlasThreads nothing(1);
  CHECK(ScopedBlasThreads::current() == 0);
}

// Skipped where the BLAS is not OpenBLAS (scripts/setup installs it).
TEST_CASE("solver: a BLAS thread guard sets OpenBLAS' count and restores it" *
          doctest::skip(!ScopedBlasThreads::available())) {
  const int before = ScopedBlasThreads::current();
  CHECK(before >= 1);
  {
    ScopedBlasThreads one(1);
    CHECK(ScopedBlasThreads::current() == 1);
  }
  CHECK(ScopedBlasThreads::current() == before);
  // Overlapping guards, not nested (as two deformers' setups on two threads): the count
  // before the first comes back when the last ends, not the first one's 1.
  auto first = std::make_unique<ScopedBlasThreads>(1);
  auto second = std::make_unique<ScopedBlasThreads>(1);
  first.reset();
  CHECK(ScopedBlasThreads::current() == 1);
  second.reset();
  CHECK(ScopedBlasThreads::current() == before);
}
