#include "cholmod_factor.h"

#include <chrono>
#include <cmath>

#include <omp.h>

#include "checks.h"
#include "page_populate.h"

namespace lapis::solver::detail {
namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// Runs the OpenMP regions opened on this thread with one thread each, for its lifetime.
// CHOLMOD's supernodal numeric factorization opens parallel regions of a fixed 4 threads
// (CHOLMOD_OMP_NUM_THREADS) around the copies and zeroing between supernodes — thousands per
// factorization, most on a few KB. On two cores the hand-offs cost more than the copies: the
// 12.5-GFlop factor of a 50K-vertex merge took ~560 instead of ~850 ms (medians of five
// alternating runs; 1.0 instead of 1.2 s with glibc's malloc), alone or beside a second
// factorization. The BLAS, which does the flops, has its own threads (blas_threads.h).
// max-active-levels is per thread in libgomp (OpenMP 5), so other threads keep their
// parallelism.
class SerialOpenMP {
 public:
  SerialOpenMP() : levels_(omp_get_max_active_levels()) { omp_set_max_active_levels(0); }
  ~SerialOpenMP() { omp_set_max_active_levels(levels_); }
  SerialOpenMP(const SerialOpenMP&) = delete;
  SerialOpenMP& operator=(const SerialOpenMP&) = delete;

 private:
  int levels_;
};

}  // namespace

CholmodFactor::~CholmodFactor() {
  free_factor();
  if (symbolic_) cholmod_free_factor(&symbolic_, context_.get());
}

void CholmodFactor::free_factor() {
  if (L_) cholmod_free_factor(&L_, context_.get());
  factorized_ = false;
}

void CholmodFactor::analyze(const SparseMatrix& A, FactorKind kind, FactorReport& stats, const char* function,
                            int solve_threads, const std::vector<int>* ordering) {
  free_factor();
  if (symbolic_) cholmod_free_factor(&symbolic_, context_.get());
  cholmod_common* c = context_.get();
  c->supernodal = kind == FactorKind::Supernodal ? CHOLMOD_SUPERNODAL : CHOLMOD_SIMPLICIAL;
  c->final_ll = kind == FactorKind::Supernodal;  // simplicial stays LDL' (updown's form)
  // nmethods = 0: AMD, then METIS / nested dissection when AMD's fill is poor (CHOLMOD's
  // default rule); the best found is kept.
  c->nmethods = 0;
  const auto t0 = std::chrono::steady_clock::now();
  cholmod_sparse a = sparse_view(A, -1);
  if (ordering) {
    // cholmod_analyze_p with nmethods = 0 would also try AMD and keep the better; the given
    // ordering is meant to replace that search, so it is the only method.
    const int first_method = c->method[0].ordering;
    c->nmethods = 1;
    c->method[0].ordering = CHOLMOD_GIVEN;
    symbolic_ = cholmod_analyze_p(&a, const_cast<int*>(ordering->data()), nullptr, 0, c);
    c->nmethods = 0;
    c->method[0].ordering = first_method;
  } else {
    const std::lock_guard metis(metis_mutex());  // CHOLMOD may try METIS (cholmod_context.h)
    symbolic_ = cholmod_analyze(&a, c);
  }
  context_.check(function, ordering ? "cholmod_analyze_p" : "cholmod_analyze");
  if (!symbolic_) throw SolverFailure(std::string(function) + ": cholmod_analyze returned no factor");
  stats.analyze_ms = ms_since(t0);
  stats.ordering = ordering ? "given" : ordering_name(c->method[c->selected].ordering);
  stats.nnz_L = static_cast<std::int64_t>(c->lnz);
  stats.flops = c->fl;
  stats.kind = kind;
  n_ = static_cast<int>(A.rows());
  pattern_outer_.assign(A.outerIndexPtr(), A.outerIndexPtr() + A.outerSize() + 1);
  pattern_inner_.assign(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros());
  const int* perm = static_cast<const int*>(symbolic_->Perm);
  inverse_perm_.resize(static_cast<size_t>(n_));
  for (int k = 0; k < n_; ++k) inverse_perm_[static_cast<size_t>(perm[k])] = k;
  // Built here, not on first solve, so that solve() stays read-only (callable concurrently).
  if (symbolic_->is_super) supernodal_schedule_ = schedule_supernodes(*symbolic_, solve_threads);
}

bool CholmodFactor::analyzed_for(const SparseMatrix& A) const {
  return symbolic_ && same_pattern(A, pattern_outer_, pattern_inner_);
}

void CholmodFactor::factorize(const SparseMatrix& A, FactorReport& stats, const char* function) {
  cholmod_common* c = context_.get();
  if (!L_) {
    L_ = cholmod_copy_factor(symbolic_, c);
    context_.check(function, "cholmod_copy_factor");
  } else if (!L_->is_super && symbolic_->is_super) {
    // A simplicial LDL' factor (after updown) would be refactorized simplicially, which is
    // an order of magnitude slower on 3D problems: start again from the supernodal analysis.
    free_factor();
    L_ = cholmod_copy_factor(symbolic_, c);
    context_.check(function, "cholmod_copy_factor");
  }
  factorized_ = false;
  const auto t0 = std::chrono::steady_clock::now();
  cholmod_sparse a = sparse_view(A, -1);
  // The values of a first supernodal factorization are allocated here rather than inside
  // cholmod_factorize (which then uses them as they are) so that their pages can be faulted
  // in on another thread meanwhile (page_populate.h): the factor is the largest fresh
  // allocation of a set-up. A refactorization writes into values already resident.
  void* fresh_values = nullptr;
  if (L_->is_super && L_->xtype == CHOLMOD_PATTERN) {
    cholmod_change_factor(CHOLMOD_REAL, /*to_ll=*/1, /*to_super=*/1, /*to_packed=*/1, /*to_monotonic=*/1, L_, c);
    context_.check(function, "cholmod_change_factor");
    fresh_values = L_->x;
  }
  {
    const PagePopulator populate(fresh_values, L_->xsize * sizeof(double));
    const SerialOpenMP serial;
    cholmod_factorize(&a, L_, c);
  }
  context_.check(function, "cholmod_factorize");
  stats.factorize_ms = ms_since(t0);
  if (c->status == CHOLMOD_NOT_POSDEF) {
    const std::ptrdiff_t column = failed_column(L_);
    throw NotPositiveDefinite(std::string(function) + ": matrix is not positive definite (pivot " +
                                  std::to_string(column) + " is not positive)",
                              column);
  }
  stats.nnz_L = static_cast<std::int64_t>(c->lnz);
  stats.flops = c->fl;
  factorized_ = true;
}

DenseMatrix CholmodFactor::solve(const DenseMatrix& B, const char* function, int threads, bool use_cholmod) const {
  if (!use_cholmod && L_->is_super && L_->xtype == CHOLMOD_REAL) {
    if (threads <= 0 || threads == supernodal_schedule_.threads)
      return solve_supernodal_llt(*L_, supernodal_schedule_, B);
    return solve_supernodal_llt(*L_, schedule_supernodes(*L_, threads), B);
  }
  if (!use_cholmod && !L_->is_super && !L_->is_ll && L_->xtype == CHOLMOD_REAL) {
    if (threads <= 0) threads = omp_get_max_threads();
    if (schedule_threads_ != threads || !schedule_matches(schedule_, *L_)) {
      schedule_ = schedule_subtrees(*L_, threads);
      schedule_threads_ = threads;
    }
    return solve_simplicial_ldlt(*L_, schedule_, B);
  }
  cholmod_dense b = dense_view(B);
  cholmod_common* c = context_.get();
  cholmod_dense* x = cholmod_solve(CHOLMOD_A, L_, &b, c);
  if (!x) context_.check(function, "cholmod_solve");
  if (!x) throw SolverFailure(std::string(function) + ": cholmod_solve returned nothing");
  DenseMatrix out = to_eigen(*x);
  cholmod_free_dense(&x, c);
  return out;
}

void CholmodFactor::to_simplicial_ldl(const char* function) {
  if (!L_->is_super && !L_->is_ll) return;
  cholmod_change_factor(CHOLMOD_REAL, /*to_ll=*/0, /*to_super=*/0, /*to_packed=*/1,
                        /*to_monotonic=*/1, L_, context_.get());
  context_.check(function, "cholmod_change_factor");
}

void CholmodFactor::updown(bool update, const SparseMatrix& C, const char* function) {
  // cholmod_updown works on the permuted matrix P A P': C's rows must be permuted alike,
  // and sorted within each column.
  SparseMatrix Cp(C.rows(), C.cols());
  {
    std::vector<Eigen::Triplet<double, int>> t;
    t.reserve(static_cast<size_t>(C.nonZeros()));
    for (int j = 0; j < C.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(C, j); it; ++it)
        t.emplace_back(permuted(static_cast<int>(it.row())), j, it.value());
    Cp.setFromTriplets(t.begin(), t.end());
    Cp.makeCompressed();
  }
  cholmod_sparse cs = sparse_view(Cp, 0);
  cholmod_updown(update ? 1 : 0, &cs, L_, context_.get());
  context_.check(function, "cholmod_updown");
}

bool CholmodFactor::can_update_diagonal() const {
  return diagonal_updown_available() && L_ && !L_->is_super && !L_->is_ll;
}

std::ptrdiff_t CholmodFactor::update_diagonal(const std::vector<std::pair<int, double>>& deltas, int threads) {
  std::vector<std::pair<int, double>> permuted_deltas;
  permuted_deltas.reserve(deltas.size());
  for (const auto& [i, d] : deltas)
    if (d != 0) permuted_deltas.emplace_back(permuted(i), d);
  const std::ptrdiff_t bad = diagonal_updown(*L_, permuted_deltas, diagonal_work_, threads);
  const int* perm = static_cast<const int*>(L_->Perm);
  return bad < 0 ? -1 : (perm ? perm[bad] : bad);
}

std::ptrdiff_t CholmodFactor::first_bad_pivot() const {
  const int* Lp = static_cast<const int*>(L_->p);
  const double* Lx = static_cast<const double*>(L_->x);
  const int* perm = static_cast<const int*>(L_->Perm);
  for (size_t j = 0; j < L_->n; ++j) {
    const double d = Lx[Lp[j]];
    if (!(std::isfinite(d) && d > 0)) return perm ? perm[j] : static_cast<std::ptrdiff_t>(j);
  }
  return -1;
}

std::vector<double> CholmodFactor::path_work() const {
  // In a simplicial factor the parent of column j is its smallest off-diagonal row index;
  // parents have larger indices than children, so one backward sweep sums the paths.
  const int* Lp = static_cast<const int*>(L_->p);
  const int* Li = static_cast<const int*>(L_->i);
  const int* Lnz = static_cast<const int*>(L_->nz);
  const size_t n = L_->n;
  std::vector<double> work(n, 0.0);
  for (size_t jj = n; jj-- > 0;) {
    int parent = -1;
    for (int k = Lp[jj] + 1; k < Lp[jj] + Lnz[jj]; ++k)
      if (parent < 0 || Li[k] < parent) parent = Li[k];
    work[jj] = static_cast<double>(Lnz[jj]) + (parent >= 0 ? work[static_cast<size_t>(parent)] : 0.0);
  }
  return work;
}

void CholmodFactor::take_factor_from(CholmodFactor& other) {
  // Factors belong to their common's allocator only in name (malloc underneath), so a factor
  // made with another context may be freed with this one.
  free_factor();
  L_ = other.L_;
  other.L_ = nullptr;
  factorized_ = other.factorized_;
  other.factorized_ = false;
}

std::unique_ptr<CholmodFactor> CholmodFactor::clone_symbolic(const char* function) const {
  auto out = std::make_unique<CholmodFactor>();
  out->symbolic_ = cholmod_copy_factor(symbolic_, out->context_.get());
  out->context_.check(function, "cholmod_copy_factor");
  out->n_ = n_;
  out->pattern_outer_ = pattern_outer_;
  out->pattern_inner_ = pattern_inner_;
  out->inverse_perm_ = inverse_perm_;
  out->supernodal_schedule_ = supernodal_schedule_;
  out->context_.get()->supernodal = context_.get()->supernodal;
  out->context_.get()->final_ll = context_.get()->final_ll;
  return out;
}

}  // namespace lapis::solver::detail
