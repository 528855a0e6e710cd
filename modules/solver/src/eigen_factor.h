// Private: Eigen's SimplicialLDLT behind the same small interface as CholmodFactor — the
// independent reference that tests cross-check CHOLMOD against.
#pragma once

#include <Eigen/SparseCholesky>

#include <chrono>
#include <string>

#include "lapis/core/error.h"
#include "lapis/solver/types.h"

namespace lapis::solver::detail {

class EigenFactor {
 public:
  void analyze(const SparseMatrix& A, FactorReport& stats) {
    const auto t0 = std::chrono::steady_clock::now();
    ldlt_.analyzePattern(A);
    stats.analyze_ms = ms_since(t0);
    stats.ordering = "AMD (Eigen)";
    stats.kind = FactorKind::Simplicial;
    analyzed_ = true;
    factorized_ = false;
  }
  bool analyzed() const { return analyzed_; }

  void factorize(const SparseMatrix& A, FactorReport& stats, const char* function) {
    factorized_ = false;
    const auto t0 = std::chrono::steady_clock::now();
    ldlt_.factorize(A);
    stats.factorize_ms = ms_since(t0);
    if (ldlt_.info() != Eigen::Success)
      throw NotPositiveDefinite(std::string(function) + ": matrix is not positive definite (Eigen LDLT failed)", -1);
    // LDL' also factors indefinite matrices: positive definiteness is positive pivots.
    const Eigen::VectorXd& d = ldlt_.vectorD();
    for (Eigen::Index k = 0; k < d.size(); ++k) {
      if (!(std::isfinite(d[k]) && d[k] > 0)) {
        const std::ptrdiff_t column = ldlt_.permutationP().indices().size() ? ldlt_.permutationPinv().indices()[k] : k;
        throw NotPositiveDefinite(std::string(function) + ": matrix is not positive definite (pivot " +
                                      std::to_string(column) + " is not positive)",
                                  column);
      }
    }
    stats.nnz_L = ldlt_.matrixL().nestedExpression().nonZeros() + d.size();
    factorized_ = true;
  }
  bool factorized() const { return factorized_; }

  DenseMatrix solve(const DenseMatrix& B) const { return ldlt_.solve(B); }

 private:
  static double ms_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  }

  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower> ldlt_;
  bool analyzed_ = false;
  bool factorized_ = false;
};

}  // namespace lapis::solver::detail
