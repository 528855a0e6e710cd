#include "lapis/solver/eigenpairs.h"

#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsShiftSolver.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <string>

#include "checks.h"
#include "shift_invert_operator.h"

namespace lapis::solver {
namespace {

constexpr const char* kFn = "solver::smallest_eigenpairs()";

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void check_input(const SparseMatrix& K, const SparseMatrix& M, int k, const EigenOptions& o) {
  detail::require_square(K, kFn);
  detail::require_square(M, kFn);
  detail::require_finite(K, kFn);
  detail::require_finite(M, kFn);
  if (M.rows() != K.rows())
    throw InvalidArgument(std::string(kFn) + ": M is " + detail::dims(M.rows(), M.cols()) + ", expected " +
                          detail::dims(K.rows(), K.cols()) + " like K");
  if (k < 1 || k >= K.rows())
    throw InvalidArgument(std::string(kFn) + ": k = " + std::to_string(k) + " eigenpairs of a " +
                          std::to_string(K.rows()) + "-row problem, expected 1 <= k < " + std::to_string(K.rows()));
  if (o.shift && !std::isfinite(*o.shift)) throw InvalidArgument(std::string(kFn) + ": the shift is not finite");
  if (!(o.relative_shift > 0) || !(o.tolerance > 0) || o.max_restarts < 1 || o.basis_size < 0)
    throw InvalidArgument(std::string(kFn) +
                          ": expected relative_shift > 0, tolerance > 0, max_restarts >= 1, basis_size >= 0");
}

// max_j K_jj / M_jj: of the order of the largest eigenvalue (exactly the largest Rayleigh
// quotient over unit vectors), the scale of the default shift and of the residuals.
double spectral_scale(const SparseMatrix& K, const SparseMatrix& M) {
  const Eigen::VectorXd kd = K.diagonal(), md = M.diagonal();
  double s = 0;
  for (Eigen::Index j = 0; j < kd.size(); ++j)
    if (md[j] > 0) s = std::max(s, kd[j] / md[j]);
  return s > 0 ? s : 1.0;
}

double max_residual(const SparseMatrix& K, const SparseMatrix& M, const Eigenpairs& e, double scale) {
  double worst = 0;
  for (Eigen::Index i = 0; i < e.values.size(); ++i) {
    const Eigen::VectorXd Mphi = M * e.vectors.col(i);
    const Eigen::VectorXd r = K * e.vectors.col(i) - e.values[i] * Mphi;
    worst = std::max(worst, r.norm() / (scale * Mphi.norm()));
  }
  return worst;
}

// Ascending order of the values, columns permuted alike.
void sort_ascending(Eigenpairs& e) {
  std::vector<Eigen::Index> order(static_cast<size_t>(e.values.size()));
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) { return e.values[a] < e.values[b]; });
  Eigenpairs sorted;
  sorted.values.resize(e.values.size());
  sorted.vectors.resize(e.vectors.rows(), e.vectors.cols());
  for (size_t c = 0; c < order.size(); ++c) {
    sorted.values[static_cast<Eigen::Index>(c)] = e.values[order[c]];
    sorted.vectors.col(static_cast<Eigen::Index>(c)) = e.vectors.col(order[c]);
  }
  e.values = std::move(sorted.values);
  e.vectors = std::move(sorted.vectors);
}

Eigenpairs dense_eigenpairs(const SparseMatrix& K, const SparseMatrix& M, int k) {
  const Eigen::MatrixXd Kd(K), Md(M);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Kd, Md);
  if (es.info() != Eigen::Success)
    throw NoConvergence(std::string(kFn) + ": the dense reference (Eigen) did not converge (is M positive definite?)",
                        0);
  Eigenpairs e;
  e.values = es.eigenvalues().head(k);
  e.vectors = es.eigenvectors().leftCols(k);
  return e;
}

Eigenpairs lanczos_eigenpairs(const SparseMatrix& K, const SparseMatrix& M, int k, double sigma, const EigenOptions& o,
                              EigenReport& report) {
  const int n = static_cast<int>(K.rows());
  const int ncv =
      o.basis_size > 0 ? std::min(std::max(o.basis_size, k + 1), n) : std::min(std::max(2 * k + 1, k + 20), n);
  detail::ShiftInvertOperator op(K, M);
  Spectra::SparseSymMatProd<double, Eigen::Lower, Eigen::ColMajor, int> bop(M);
  const auto t0 = std::chrono::steady_clock::now();
  try {
    Spectra::SymGEigsShiftSolver<detail::ShiftInvertOperator, decltype(bop), Spectra::GEigsMode::ShiftInvert> eigs(
        op, bop, k, ncv, sigma);
    report.factorize_ms = ms_since(t0);
    eigs.init();
    const auto converged = eigs.compute(Spectra::SortRule::LargestMagn, o.max_restarts, o.tolerance);
    report.restarts = static_cast<int>(eigs.num_iterations());
    report.solves = op.solves();
    if (eigs.info() != Spectra::CompInfo::Successful)
      throw NoConvergence(std::string(kFn) + ": shift-invert Lanczos converged " + std::to_string(converged) + " of " +
                              std::to_string(k) + " eigenpairs in " + std::to_string(o.max_restarts) +
                              " restarts (raise max_restarts or basis_size, or loosen tolerance)",
                          static_cast<int>(converged));
    Eigenpairs e;
    e.values = eigs.eigenvalues();
    e.vectors = eigs.eigenvectors();
    return e;
  } catch (const NotPositiveDefinite& err) {
    throw NotPositiveDefinite(std::string(kFn) + ": K - sigma M with sigma = " + std::to_string(sigma) +
                                  " is not positive definite (is K semi-definite, M definite, sigma below the "
                                  "spectrum?): " +
                                  err.what(),
                              err.column());
  }
}

}  // namespace

Eigenpairs smallest_eigenpairs(const SparseMatrix& K, const SparseMatrix& M, int k, const EigenOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  check_input(K, M, k, o);
  const double scale = spectral_scale(K, M);
  EigenReport report;
  report.backend = o.backend;
  report.shift = o.shift ? *o.shift : -o.relative_shift * scale;
  Eigenpairs e =
      o.backend == Backend::Eigen ? dense_eigenpairs(K, M, k) : lanczos_eigenpairs(K, M, k, report.shift, o, report);
  sort_ascending(e);
  report.max_residual = max_residual(K, M, e, scale);
  report.total_ms = ms_since(t0);
  e.report = report;
  return e;
}

}  // namespace lapis::solver
