// A Cholesky factor that can be modified in place: A ± C Cᵀ by CHOLMOD's rank-k
// update/downdate, and the change of diagonal soft-constraint weights that hair sketching
// makes on every stroke (thesis §4.4.2). Each modification is timed, and a cost model
// calibrated at run time picks update/downdate or a numeric refactorization, whichever it
// predicts cheaper; the report says which ran.
#pragma once

#include <memory>
#include <span>
#include <string>

#include "lapis/solver/types.h"

namespace lapis::solver {

enum class ModifyMethod {
  Auto,  // let the cost model choose (the default)
  UpdateDowndate,
  Refactorize,
};

const char* to_string(ModifyMethod m);

// What one modification did.
struct ModifyReport {
  ModifyMethod method = ModifyMethod::UpdateDowndate;  // what actually ran (never Auto)
  int rank = 0;                                        // columns of C (update + downdate)
  double predicted_updown_ms = 0;                      // the cost model's predictions
  double predicted_refactor_ms = 0;
  double ms = 0;  // measured wall time
};

struct UpdatableCholeskyOptions {
  Backend backend = Backend::Cholmod;  // Eigen: refactorizes on every modification (reference)
  ModifyMethod method = ModifyMethod::Auto;
  // Threads of the solve (subtrees of the elimination tree run in parallel); 0: OpenMP's
  // default. The result does not depend on it beyond round-off.
  int threads = 0;
};

class UpdatableCholesky {
 public:
  explicit UpdatableCholesky(UpdatableCholeskyOptions options = {});
  ~UpdatableCholesky();
  UpdatableCholesky(UpdatableCholesky&&) noexcept;
  UpdatableCholesky& operator=(UpdatableCholesky&&) noexcept;
  UpdatableCholesky(const UpdatableCholesky&) = delete;
  UpdatableCholesky& operator=(const UpdatableCholesky&) = delete;

  // A  n by n SPD. Factorizes (supernodal, then converted to the simplicial LDL' that
  // cholmod_updown needs). Diagonal weights start at zero: A already contains them.
  void compute(const SparseMatrix& A);
  // Factorizes A₀ + diag(w) and remembers w as the current diagonal weights: A₀ may be
  // singular on its own (the grid bi-Laplacian DᵀD is), the weights make it definite.
  // A₀ must store its diagonal. w  n entries, finite and ≥ 0.
  void compute(const SparseMatrix& A0, const Eigen::VectorXd& diagonal_weights);

  // A += C Cᵀ and A -= C Cᵀ for C  n by r. A downdate that would make A indefinite throws
  // NotPositiveDefinite and leaves the object solving the previous A.
  ModifyReport update(const SparseMatrix& C);
  ModifyReport downdate(const SparseMatrix& C);

  // Sets the diagonal soft-constraint weights w_i (A = A₀ + Σ w_i e_i e_iᵀ, the weights
  // this object has been told so far) of `indices` to `weights`: increases become one
  // update, decreases one downdate. Weights must be finite and ≥ 0.
  ModifyReport set_diagonal_weights(std::span<const int> indices, std::span<const double> weights);
  // The weight currently added to A(i, i) through set_diagonal_weights.
  double diagonal_weight(int i) const;

  // B  n by k; returns X with A X = B for the current A.
  DenseMatrix solve(const DenseMatrix& B) const;

  // The matrix the factor currently represents (A₀ plus all modifications), lower+upper.
  const SparseMatrix& matrix() const;
  int rows() const;
  const FactorReport& report() const;
  const ModifyReport& last_report() const;

  // Forces every later modification to one method (benchmarks compare them).
  void set_method(ModifyMethod method);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lapis::solver
