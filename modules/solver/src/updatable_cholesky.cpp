#include "lapis/solver/updatable_cholesky.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>

#include "checks.h"
#include "cholmod_factor.h"
#include "eigen_factor.h"
#include "lapis/core/format.h"
#include "updown_cost_model.h"

namespace lapis::solver {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

// sign = +1: A + C C', sign = -1: A - C C'.
SparseMatrix add_outer(const SparseMatrix& A, const SparseMatrix& C, double sign) {
  SparseMatrix CCt = C * SparseMatrix(C.transpose());
  SparseMatrix out = A + sign * CCt;
  out.makeCompressed();
  return out;
}

// A(i, i) += d for each (i, d); entries that are not stored yet are inserted.
void add_to_diagonal(SparseMatrix& A, const std::vector<std::pair<int, double>>& deltas) {
  bool inserted = false;
  for (const auto& [i, d] : deltas) {
    const int* begin = A.innerIndexPtr() + A.outerIndexPtr()[i];
    const int* end = A.innerIndexPtr() + A.outerIndexPtr()[i + 1];
    const int* it = std::lower_bound(begin, end, i);
    if (A.isCompressed() && it != end && *it == i) {
      A.valuePtr()[it - A.innerIndexPtr()] += d;
    } else {
      A.coeffRef(i, i) += d;
      inserted = true;
    }
  }
  if (inserted) A.makeCompressed();
}

// Columns sqrt(|d_i|) e_i for the entries of `deltas` with the given sign. Built column by
// column (one entry each): setFromTriplets would sort through an n-long temporary on every
// edit, for matrices the one-sweep kernel only reads the first rows of.
SparseMatrix diagonal_columns(int n, const std::vector<std::pair<int, double>>& deltas, double sign) {
  int count = 0;
  for (const auto& [i, d] : deltas) count += d * sign > 0;
  SparseMatrix C(n, count);
  // Eigen 3.4's makeCompressed() after reserve() reads and writes outerIndex[1], which an
  // n by 0 matrix does not have; an empty matrix is compressed already.
  if (count == 0) return C;
  C.reserve(Eigen::VectorXi::Constant(count, 1));
  int col = 0;
  for (const auto& [i, d] : deltas)
    if (d * sign > 0) C.insert(i, col++) = std::sqrt(std::abs(d));
  C.makeCompressed();
  return C;
}

}  // namespace

struct UpdatableCholesky::Impl {
  UpdatableCholeskyOptions options;
  FactorReport stats;
  ModifyReport report;
  SparseMatrix A;
  std::vector<double> weights;
  std::unique_ptr<detail::CholmodFactor> factor;
  std::unique_ptr<detail::EigenFactor> eigen;
  detail::UpdownCostModel cost;
  int n = 0;

  bool ready() const { return factor || eigen; }

  // Numeric factorization of `A_new` into a fresh factor; replaces the current one only on
  // success, so a matrix that is not positive definite leaves the previous state intact.
  void refactorize(const SparseMatrix& A_new, const char* fn) {
    const auto t0 = Clock::now();
    if (options.backend == Backend::Eigen) {
      auto fresh = std::make_unique<detail::EigenFactor>();
      fresh->analyze(A_new, stats);
      fresh->factorize(A_new, stats, fn);
      eigen = std::move(fresh);
    } else {
      // A general C C' can add entries outside the analyzed pattern: analyze anew then
      // (diagonal weight changes, the common case, keep the pattern and the analysis).
      const bool same_pattern = factor->analyzed_for(A_new);
      std::unique_ptr<detail::CholmodFactor> fresh;
      if (same_pattern) {
        fresh = factor->clone_symbolic(fn);
      } else {
        fresh = std::make_unique<detail::CholmodFactor>();
        fresh->analyze(A_new, FactorKind::Supernodal, stats, fn);
      }
      fresh->factorize(A_new, stats, fn);
      fresh->to_simplicial_ldl(fn);
      stats.kind = FactorKind::Simplicial;
      factor = std::move(fresh);
      if (!same_pattern) cost.set_paths(factor->path_work());
      cost.observe_refactor(ms_since(t0));
    }
    A = A_new;
  }

  // First permuted row of each column of C: where its rank-1 modification starts.
  std::vector<int> first_rows(const SparseMatrix& C) const {
    std::vector<int> rows;
    rows.reserve(static_cast<size_t>(C.cols()));
    for (int j = 0; j < C.outerSize(); ++j) {
      int first = -1;
      for (SparseMatrix::InnerIterator it(C, j); it; ++it) {
        const int p = factor->permuted(static_cast<int>(it.row()));
        if (first < 0 || p < first) first = p;
      }
      if (first >= 0) rows.push_back(first);
    }
    return rows;
  }

  ModifyMethod choose(double work) {
    report.predicted_updown_ms = cost.predict_updown_ms(work);
    report.predicted_refactor_ms = cost.predict_refactor_ms();
    if (options.backend == Backend::Eigen) return ModifyMethod::Refactorize;
    if (options.method != ModifyMethod::Auto) return options.method;
    return report.predicted_updown_ms <= report.predicted_refactor_ms ? ModifyMethod::UpdateDowndate
                                                                      : ModifyMethod::Refactorize;
  }

  // L D L' ± C C' in place. A failed downdate is undone by the matching update (and, should
  // that not restore positive pivots, by refactorizing the unchanged A) before throwing.
  void updown(bool update, const SparseMatrix& C, const char* fn) {
    factor->updown(update, C, fn);
    if (update) return;
    const std::ptrdiff_t bad = factor->first_bad_pivot();
    if (bad < 0) return;
    factor->updown(true, C, fn);
    if (factor->first_bad_pivot() >= 0) refactorize(A, fn);
    throw NotPositiveDefinite(std::string(fn) + ": downdate makes the matrix indefinite (pivot " + std::to_string(bad) +
                                  " is not positive); previous factor kept",
                              bad);
  }

  // Diagonal changes of both signs in one sweep. A pivot that would not stay positive leaves
  // the factor half modified: it is rebuilt from the unchanged A before throwing.
  void update_diagonal(const std::vector<std::pair<int, double>>& deltas, const char* fn) {
    const std::ptrdiff_t bad = factor->update_diagonal(deltas, options.threads);
    if (bad < 0) return;
    refactorize(A, fn);
    throw NotPositiveDefinite(std::string(fn) + ": downdate makes the matrix indefinite (pivot " + std::to_string(bad) +
                                  " is not positive); previous factor kept",
                              bad);
  }

  // A downdate after an update in the same modification: a failure undoes the update too.
  void updown_down_after(const SparseMatrix& up, const SparseMatrix& down, const char* fn) {
    try {
      updown(false, down, fn);
    } catch (const NotPositiveDefinite&) {
      if (up.cols() > 0) factor->updown(false, up, fn);  // back to the previous A
      throw;
    }
  }

  // The whole modification A + up up' - down down'. When `diagonal` is given, the modification is exactly those
  // diagonal changes (set_diagonal_weights) and A is updated in place in O(k) instead of by
  // two O(nnz(A)) sparse sums: at 50K unknowns that is most of a small edit's cost.
  void modify(const SparseMatrix& up, const SparseMatrix& down, const char* fn,
              const std::vector<std::pair<int, double>>* diagonal = nullptr) {
    if (!ready()) throw InvalidArgument(std::string(fn) + ": no factorization (call compute() first)");
    const auto t0 = Clock::now();
    report = {};
    report.rank = static_cast<int>(up.cols() + down.cols());
    double work = 0;
    if (factor) {
      std::vector<int> rows = first_rows(up);
      const std::vector<int> rows_down = first_rows(down);
      rows.insert(rows.end(), rows_down.begin(), rows_down.end());
      work = cost.work(rows);
    }
    report.method = choose(work);
    if (report.rank == 0) {
      report.method = ModifyMethod::UpdateDowndate;
    } else if (report.method == ModifyMethod::Refactorize) {
      SparseMatrix A_new = A;
      if (diagonal) {
        add_to_diagonal(A_new, *diagonal);
      } else {
        if (up.cols() > 0) A_new = add_outer(A_new, up, +1);
        if (down.cols() > 0) A_new = add_outer(A_new, down, -1);
      }
      refactorize(A_new, fn);
    } else {
      const auto t_updown = Clock::now();
      if (diagonal && factor && factor->can_update_diagonal()) {
        update_diagonal(*diagonal, fn);
      } else {
        if (up.cols() > 0) updown(true, up, fn);
        if (down.cols() > 0) updown_down_after(up, down, fn);
      }
      cost.observe_updown(work, ms_since(t_updown));
      if (diagonal) {
        add_to_diagonal(A, *diagonal);
      } else {
        if (up.cols() > 0) A = add_outer(A, up, +1);
        if (down.cols() > 0) A = add_outer(A, down, -1);
      }
    }
    report.ms = ms_since(t0);
  }

  void check_columns(const SparseMatrix& C, const char* fn) const {
    if (C.rows() != n)
      throw InvalidArgument(std::string(fn) + ": C is " + detail::dims(C.rows(), C.cols()) + ", expected " +
                            std::to_string(n) + " rows");
    detail::require_finite(C, fn);
  }
};

UpdatableCholesky::UpdatableCholesky(UpdatableCholeskyOptions options) : impl_(std::make_unique<Impl>()) {
  impl_->options = options;
  impl_->stats.backend = options.backend;
  impl_->stats.kind = FactorKind::Simplicial;
}
UpdatableCholesky::~UpdatableCholesky() = default;
UpdatableCholesky::UpdatableCholesky(UpdatableCholesky&&) noexcept = default;
UpdatableCholesky& UpdatableCholesky::operator=(UpdatableCholesky&&) noexcept = default;

void UpdatableCholesky::compute(const SparseMatrix& A) { compute(A, Eigen::VectorXd::Zero(A.rows())); }

void UpdatableCholesky::compute(const SparseMatrix& A0, const Eigen::VectorXd& diagonal_weights) {
  constexpr const char* fn = "solver::UpdatableCholesky::compute()";
  detail::require_square(A0, fn);
  detail::require_finite(A0, fn);
  Impl& m = *impl_;
  if (diagonal_weights.size() != A0.rows())
    throw InvalidArgument(std::string(fn) + ": " + std::to_string(diagonal_weights.size()) +
                          " diagonal weights, expected " + std::to_string(A0.rows()));
  if (!diagonal_weights.allFinite() || diagonal_weights.minCoeff() < 0)
    throw InvalidArgument(std::string(fn) + ": diagonal weights must be finite and >= 0");
  SparseMatrix A = A0;
  for (Eigen::Index i = 0; i < A.rows(); ++i)
    if (diagonal_weights[i] != 0) A.coeffRef(i, i) += diagonal_weights[i];
  A.makeCompressed();
  m.n = static_cast<int>(A.rows());
  m.stats.n = m.n;
  m.stats.nnz_A = A.nonZeros();
  m.weights.assign(diagonal_weights.data(), diagonal_weights.data() + diagonal_weights.size());
  m.factor.reset();
  m.eigen.reset();
  if (m.options.backend == Backend::Eigen) {
    m.refactorize(A, fn);
    return;
  }
  // Supernodal factorization (fast, BLAS) converted to the simplicial LDL' that
  // cholmod_updown modifies: much faster than factorizing simplicially on 3D problems.
  auto factor = std::make_unique<detail::CholmodFactor>();
  factor->analyze(A, FactorKind::Supernodal, m.stats, fn);
  const auto t0 = Clock::now();
  factor->factorize(A, m.stats, fn);
  factor->to_simplicial_ldl(fn);
  const double refactor_ms = ms_since(t0);
  m.stats.kind = FactorKind::Simplicial;
  m.factor = std::move(factor);
  m.A = std::move(A);
  m.cost.reset(m.factor->path_work(), refactor_ms);

  // Calibrate the update/downdate constant with a real rank-8 update and its downdate (A is
  // unchanged up to round-off); the fastest of three runs, since one timing on a busy machine
  // can be off by an order of magnitude (a thread descheduled for a time slice in a 1 ms run).
  const int k = std::min(8, m.n);
  std::vector<Eigen::Triplet<double, int>> t;
  for (int j = 0; j < k; ++j) {
    const int i = static_cast<int>((static_cast<long long>(j) * m.n) / k);
    t.emplace_back(i, j, 1e-3 * std::sqrt(std::abs(m.A.coeff(i, i)) + 1e-300));
  }
  SparseMatrix C(m.n, k);
  C.setFromTriplets(t.begin(), t.end());
  C.makeCompressed();
  const double work = 2 * m.cost.work(m.first_rows(C));
  // The same kernel as set_diagonal_weights() (C is diagonal).
  std::vector<std::pair<int, double>> up, down;
  for (const auto& e : t) {
    up.emplace_back(e.row(), e.value() * e.value());
    down.emplace_back(e.row(), -e.value() * e.value());
  }
  double fastest = 0;
  for (int rep = 0; rep < 3; ++rep) {
    const auto t1 = Clock::now();
    if (m.factor->can_update_diagonal()) {
      m.update_diagonal(up, fn);
      m.update_diagonal(down, fn);
    } else {
      m.factor->updown(true, C, fn);
      m.factor->updown(false, C, fn);
    }
    const double ms = ms_since(t1);
    fastest = rep == 0 ? ms : std::min(fastest, ms);
  }
  m.cost.observe_updown(work, fastest);
}

ModifyReport UpdatableCholesky::update(const SparseMatrix& C) {
  constexpr const char* fn = "solver::UpdatableCholesky::update()";
  impl_->check_columns(C, fn);
  impl_->modify(C, SparseMatrix(impl_->n, 0), fn);
  return impl_->report;
}

ModifyReport UpdatableCholesky::downdate(const SparseMatrix& C) {
  constexpr const char* fn = "solver::UpdatableCholesky::downdate()";
  impl_->check_columns(C, fn);
  impl_->modify(SparseMatrix(impl_->n, 0), C, fn);
  return impl_->report;
}

ModifyReport UpdatableCholesky::set_diagonal_weights(std::span<const int> indices, std::span<const double> weights) {
  constexpr const char* fn = "solver::UpdatableCholesky::set_diagonal_weights()";
  Impl& m = *impl_;
  if (indices.size() != weights.size())
    throw InvalidArgument(std::string(fn) + ": " + std::to_string(indices.size()) + " indices but " +
                          std::to_string(weights.size()) + " weights");
  std::map<int, double> target;  // a repeated index: the last weight wins
  for (size_t k = 0; k < indices.size(); ++k) {
    const int i = indices[k];
    if (i < 0 || i >= m.n)
      throw InvalidArgument(std::string(fn) + ": index " + std::to_string(i) + " out of range [0, " +
                            std::to_string(m.n) + ")");
    if (!(std::isfinite(weights[k]) && weights[k] >= 0))
      throw InvalidArgument(std::string(fn) + ": weight " + format_number(weights[k]) + " of index " +
                            std::to_string(i) + " is not finite and >= 0");
    target[i] = weights[k];
  }
  std::vector<std::pair<int, double>> deltas;
  for (const auto& [i, w] : target)
    if (w != m.weights[static_cast<size_t>(i)]) deltas.emplace_back(i, w - m.weights[static_cast<size_t>(i)]);
  m.modify(diagonal_columns(m.n, deltas, +1), diagonal_columns(m.n, deltas, -1), fn, &deltas);
  for (const auto& [i, w] : target) m.weights[static_cast<size_t>(i)] = w;
  return m.report;
}

double UpdatableCholesky::diagonal_weight(int i) const {
  if (i < 0 || i >= impl_->n)
    throw InvalidArgument("solver::UpdatableCholesky::diagonal_weight(): index " + std::to_string(i) +
                          " out of range [0, " + std::to_string(impl_->n) + ")");
  return impl_->weights[static_cast<size_t>(i)];
}

DenseMatrix UpdatableCholesky::solve(const DenseMatrix& B) const {
  constexpr const char* fn = "solver::UpdatableCholesky::solve()";
  const Impl& m = *impl_;
  if (!m.ready()) throw InvalidArgument(std::string(fn) + ": no factorization (call compute() first)");
  detail::require_rows(B, m.n, fn);
  const auto t0 = Clock::now();
  DenseMatrix X = m.factor ? m.factor->solve(B, fn, m.options.threads) : m.eigen->solve(B);
  impl_->stats.solve_ms = ms_since(t0);
  return X;
}

const SparseMatrix& UpdatableCholesky::matrix() const { return impl_->A; }
int UpdatableCholesky::rows() const { return impl_->n; }
const FactorReport& UpdatableCholesky::report() const { return impl_->stats; }
const ModifyReport& UpdatableCholesky::last_report() const { return impl_->report; }
void UpdatableCholesky::set_method(ModifyMethod method) { impl_->options.method = method; }

}  // namespace lapis::solver
