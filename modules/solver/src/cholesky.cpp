#include "lapis/solver/cholesky.h"

#include <chrono>

#include "checks.h"
#include "cholmod_factor.h"
#include "eigen_factor.h"

namespace lapis::solver {

struct Cholesky::Impl {
  CholeskyOptions options;
  FactorReport stats;
  detail::CholmodFactor cholmod;
  detail::EigenFactor eigen;
  bool analyzed = false;
  int n = 0;
};

Cholesky::Cholesky(CholeskyOptions options) : impl_(std::make_unique<Impl>()) {
  impl_->options = options;
  impl_->stats.backend = options.backend;
  impl_->stats.kind = options.backend == Backend::Eigen ? FactorKind::Simplicial : options.kind;
}
Cholesky::~Cholesky() = default;
Cholesky::Cholesky(Cholesky&&) noexcept = default;
Cholesky& Cholesky::operator=(Cholesky&&) noexcept = default;

void Cholesky::analyze(const SparseMatrix& A) { analyze_with(A, nullptr); }

void Cholesky::analyze(const SparseMatrix& A, const std::vector<int>& ordering) {
  constexpr const char* fn = "solver::Cholesky::analyze()";
  detail::require_square(A, fn);
  detail::require_permutation(ordering, static_cast<int>(A.rows()), fn);
  analyze_with(A, &ordering);
}

void Cholesky::analyze_with(const SparseMatrix& A, const std::vector<int>* ordering) {
  constexpr const char* fn = "solver::Cholesky::analyze()";
  detail::require_square(A, fn);
  if (!A.isCompressed()) return analyze_with(SparseMatrix(A), ordering);  // CHOLMOD needs compressed storage
  Impl& m = *impl_;
  m.n = static_cast<int>(A.rows());
  m.stats.n = m.n;
  m.stats.nnz_A = A.nonZeros();
  if (m.options.backend == Backend::Cholmod)
    m.cholmod.analyze(A, m.options.kind, m.stats, fn, m.options.threads, ordering);
  else
    m.eigen.analyze(A, m.stats);
  m.analyzed = true;
}

void Cholesky::factorize(const SparseMatrix& A) {
  constexpr const char* fn = "solver::Cholesky::factorize()";
  detail::require_square(A, fn);
  detail::require_finite(A, fn);
  if (!A.isCompressed()) return factorize(SparseMatrix(A));
  Impl& m = *impl_;
  if (m.options.backend == Backend::Cholmod) {
    if (!m.cholmod.analyzed_for(A)) analyze(A);
    m.cholmod.factorize(A, m.stats, fn);
  } else {
    if (!m.analyzed || m.n != A.rows()) analyze(A);
    m.eigen.factorize(A, m.stats, fn);
  }
}

void Cholesky::compute(const SparseMatrix& A) {
  analyze(A);
  factorize(A);
}

DenseMatrix Cholesky::solve(const DenseMatrix& B) const {
  constexpr const char* fn = "solver::Cholesky::solve()";
  if (!factorized()) throw InvalidArgument(std::string(fn) + ": no factorization (call factorize() first)");
  detail::require_rows(B, impl_->n, fn);
  const auto t0 = std::chrono::steady_clock::now();
  DenseMatrix X = impl_->options.backend == Backend::Cholmod
                      ? impl_->cholmod.solve(B, fn, impl_->options.threads, impl_->options.cholmod_solve)
                      : impl_->eigen.solve(B);
  impl_->stats.solve_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return X;
}

bool Cholesky::factorized() const {
  return impl_->options.backend == Backend::Cholmod ? impl_->cholmod.factorized() : impl_->eigen.factorized();
}

int Cholesky::rows() const { return impl_->n; }
const FactorReport& Cholesky::report() const { return impl_->stats; }

DenseMatrix solve_spd(const SparseMatrix& A, const DenseMatrix& B, CholeskyOptions options) {
  Cholesky chol(options);
  chol.compute(A);
  return chol.solve(B);
}

}  // namespace lapis::solver
