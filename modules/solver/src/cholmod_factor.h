// Private: one CHOLMOD factor with its own workspace. Analysis, numeric factorization,
// solve, conversion to simplicial LDL' and rank-k update/downdate; both public factor
// classes are built on it so the CHOLMOD calls live in one place.
#pragma once

#include <memory>
#include <vector>

#include "cholmod_context.h"
#include "diagonal_updown.h"
#include "simplicial_solve.h"
#include "supernodal_solve.h"

namespace lapis::solver::detail {

class CholmodFactor {
 public:
  CholmodFactor() = default;
  ~CholmodFactor();
  CholmodFactor(const CholmodFactor&) = delete;
  CholmodFactor& operator=(const CholmodFactor&) = delete;

  // Symbolic analysis of A (lower triangle read) for a factor of the given kind; fills
  // stats.ordering, nnz_L, flops, analyze_ms. Keeps A's pattern to detect changes. A
  // supernodal factor's solve is scheduled here for `solve_threads` (0: OpenMP's default).
  // `ordering`, if given, replaces CHOLMOD's choice (a permutation, checked by the caller).
  void analyze(const SparseMatrix& A, FactorKind kind, FactorReport& stats, const char* function, int solve_threads = 0,
               const std::vector<int>* ordering = nullptr);
  bool analyzed_for(const SparseMatrix& A) const;
  // Numeric factorization into the analyzed structure. Throws NotPositiveDefinite naming the
  // (un-permuted) column; the factor is then unusable until the next factorize().
  void factorize(const SparseMatrix& A, FactorReport& stats, const char* function);
  bool factorized() const { return factorized_; }

  // A X = B by Lapis' own kernels (simplicial LDL' or supernodal LL'), in parallel over
  // subtrees on `threads` threads (0: OpenMP's default); by cholmod_solve when
  // `use_cholmod` (a cross-check) or the factor is of another kind.
  DenseMatrix solve(const DenseMatrix& B, const char* function, int threads = 0, bool use_cholmod = false) const;

  // Converts the numeric factor to simplicial LDL' (what cholmod_updown modifies).
  void to_simplicial_ldl(const char* function);
  // L·D·L' ± C·C' where C's rows are in the caller's (un-permuted) ordering; permutes them.
  void updown(bool update, const SparseMatrix& C, const char* function);
  // A(i, i) += δ for each (i, δ) (un-permuted i, either sign), in place in one sweep on
  // `threads` threads (0: OpenMP's default; diagonal_updown.h); only when
  // can_update_diagonal(). Returns -1, or the un-permuted column whose pivot would not stay
  // positive: the factor is then partly modified and must be refactorized.
  bool can_update_diagonal() const;
  std::ptrdiff_t update_diagonal(const std::vector<std::pair<int, double>>& deltas, int threads = 0);
  // First column j of the simplicial LDL' factor whose pivot D(j,j) is not finite and
  // positive, un-permuted; -1 if all are.
  std::ptrdiff_t first_bad_pivot() const;

  // Per permuted column k: the sum of column counts of L along the elimination-tree path
  // from k to its root — the entries a rank-1 update starting at k touches (Davis & Hager).
  std::vector<double> path_work() const;
  // Position in the factor's ordering of original row i.
  int permuted(int i) const { return inverse_perm_[static_cast<size_t>(i)]; }

  // Moves `other`'s numeric factor into this one (same analysis assumed).
  void take_factor_from(CholmodFactor& other);
  // A new factor object sharing nothing, holding a copy of this symbolic analysis.
  std::unique_ptr<CholmodFactor> clone_symbolic(const char* function) const;

  int n() const { return n_; }

 private:
  void free_factor();

  mutable CholmodContext context_;
  cholmod_factor* L_ = nullptr;
  cholmod_factor* symbolic_ = nullptr;  // the analysis, kept for refactorization
  bool factorized_ = false;
  int n_ = 0;
  std::vector<int> pattern_outer_, pattern_inner_;
  std::vector<int> inverse_perm_;
  mutable SubtreeSchedule schedule_;  // for the simplicial solve; rebuilt when L's pattern changes
  mutable int schedule_threads_ = 0;
  SupernodalSchedule supernodal_schedule_;  // for the supernodal solve; built by analyze()
  DiagonalUpdownWork diagonal_work_;
};

}  // namespace lapis::solver::detail
