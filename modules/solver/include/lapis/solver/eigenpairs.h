// The smallest eigenpairs of a sparse symmetric generalized problem K φ = λ M φ (K positive
// semi-definite, M positive definite): the spectrum of a mesh's cotangent Laplacian behind the
// heat kernel signature (Sun et al. 2009) that Zhao et al. §3.1 use to find salient features.
// Shift-invert Lanczos (Spectra) over a Cholesky factor of K − σM, so CHOLMOD stays here.
#pragma once

#include <optional>

#include "lapis/solver/types.h"

namespace lapis::solver {

// The iteration stopped before `requested` eigenpairs met the tolerance.
class NoConvergence : public SolverFailure {
 public:
  NoConvergence(const std::string& what, int converged) : SolverFailure(what), converged_(converged) {}
  int converged() const { return converged_; }

 private:
  int converged_;
};

struct EigenOptions {
  // Cholmod: shift-invert Lanczos, the product. Eigen: a dense GeneralizedSelfAdjointEigenSolver
  // of the whole problem, O(n³): the reference for tests, for a few thousand rows at most.
  Backend backend = Backend::Cholmod;
  // The shift σ of K − σM. Unset: σ = −relative_shift · max_i K_ii / M_ii, just below the
  // spectrum's bottom (a closed mesh's Laplacian has λ₁ = 0, so σ = 0 would be singular) and far
  // enough that K − σM stays well conditioned (max_i K_ii / M_ii is of the order of λ_max).
  std::optional<double> shift;
  double relative_shift = 1e-6;
  // Lanczos basis size; 0: max(2k + 1, k + 20) capped at n (Spectra recommends ≥ 2k).
  int basis_size = 0;
  int max_restarts = 1000;
  double tolerance = 1e-12;  // Spectra's relative accuracy of the Ritz values

  bool operator==(const EigenOptions&) const = default;
};

struct EigenReport {
  Backend backend = Backend::Cholmod;
  double shift = 0;  // σ used
  int restarts = 0;  // Lanczos restarts (0 for the dense backend)
  int solves = 0;    // applications of (K − σM)⁻¹M
  // max_i ‖Kφ_i − λ_i Mφ_i‖₂ / (s ‖Mφ_i‖₂), s = max_j K_jj / M_jj: relative to the top of the
  // spectrum, so a λ₁ = 0 pair is measured too.
  double max_residual = 0;
  double factorize_ms = 0;  // Cholesky of K − σM
  double total_ms = 0;
};

struct Eigenpairs {
  Eigen::VectorXd values;  // k ascending eigenvalues λ
  DenseMatrix vectors;     // n by k, M-orthonormal: ΦᵀMΦ = I
  EigenReport report;
};

// The k smallest eigenpairs of K φ = λ M φ.
// K  n by n symmetric positive semi-definite (both triangles stored)
// M  n by n symmetric positive definite (e.g. a lumped mass matrix)
// Throws InvalidArgument for non-square or mismatched matrices, non-finite entries, k < 1 or
// k ≥ n (Lanczos needs a basis larger than k), a shift that is not finite; NotPositiveDefinite
// when K − σM is not (σ above the smallest eigenvalue, or M not definite); NoConvergence
// naming how many pairs converged.
Eigenpairs smallest_eigenpairs(const SparseMatrix& K, const SparseMatrix& M, int k, const EigenOptions& options = {});

}  // namespace lapis::solver
