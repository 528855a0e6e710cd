// Sparse Cholesky factorization of a symmetric positive definite matrix: analyze once,
// factorize (and refactorize with the same pattern), then solve many right-hand sides,
// all columns at once (x, y, z together). The one place Lapis factorizes a sparse matrix.
#pragma once

#include <memory>
#include <vector>

#include "lapis/solver/types.h"

namespace lapis::solver {

struct CholeskyOptions {
  Backend backend = Backend::Cholmod;
  // Supernodal LL' is several times faster to factorize than simplicial on 3D problems.
  FactorKind kind = FactorKind::Supernodal;
  // Threads of the solve (0: OpenMP's default).
  int threads = 0;
  // Solve with cholmod_solve instead of Lapis' parallel kernels: for cross-checks.
  bool cholmod_solve = false;
};

class Cholesky {
 public:
  explicit Cholesky(CholeskyOptions options = {});
  ~Cholesky();
  Cholesky(Cholesky&&) noexcept;
  Cholesky& operator=(Cholesky&&) noexcept;
  Cholesky(const Cholesky&) = delete;
  Cholesky& operator=(const Cholesky&) = delete;

  // A  n by n symmetric; only its lower triangle is read (the upper may be stored or left out).
  // Symbolic analysis: chooses the fill-reducing ordering. Throws InvalidArgument if A is
  // not square, SolverFailure if the backend fails.
  void analyze(const SparseMatrix& A);
  // The same with a given fill-reducing ordering (ordering[k]: the unknown eliminated k-th),
  // e.g. skeleton_nested_dissection() (ordering.h). The Eigen backend orders by its own AMD
  // (it is the reference, not a fast path). Throws InvalidArgument if `ordering` is not a
  // permutation of 0..n-1.
  void analyze(const SparseMatrix& A, const std::vector<int>& ordering);
  // Numeric factorization. Re-analyzes first if A's pattern differs from the analyzed one.
  // Throws NotPositiveDefinite (naming the column) if A is not positive definite; the
  // object then holds no factor until the next successful factorize().
  void factorize(const SparseMatrix& A);
  // analyze() + factorize().
  void compute(const SparseMatrix& A);

  // B  n by k right-hand sides; returns X with A X = B. Throws InvalidArgument on a size
  // mismatch or when nothing is factorized, and on non-finite entries of B.
  DenseMatrix solve(const DenseMatrix& B) const;

  bool factorized() const;
  int rows() const;
  const FactorReport& report() const;

 private:
  void analyze_with(const SparseMatrix& A, const std::vector<int>* ordering);
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// One-off convenience: factorize A and solve A X = B.
DenseMatrix solve_spd(const SparseMatrix& A, const DenseMatrix& B, CholeskyOptions options = {});

}  // namespace lapis::solver
