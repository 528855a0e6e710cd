// The thesis' field path (§4.4.2): factorize DᵀD + WᵀW once, then turn each constraint
// edit into a Cholesky update (added nodes) and downdate (removed nodes) through
// solver::UpdatableCholesky, and back-substitute the three right-hand sides together.
// Target-only changes touch the right-hand side alone.
#pragma once

#include <memory>

#include "lapis/hair_field/field_solver.h"
#include "lapis/solver/updatable_cholesky.h"

namespace lapis::hair_field {

class CholeskyFieldSolver final : public FieldSolver {
 public:
  // modify: how edits change the factor. Auto: the solver layer's cost model picks update/
  // downdate or refactorization per edit (timed as it runs); Refactorize: the baseline
  // the benchmark compares against; UpdateDowndate: always modify (tests of the thesis path,
  // which must not depend on timings).
  // Throws ResourceLimit when estimate_cholesky_bytes(n) exceeds options.memory_limit_bytes.
  CholeskyFieldSolver(const Grid& grid, const FieldSolverOptions& options = {},
                      solver::ModifyMethod modify = solver::ModifyMethod::Auto);
  ~CholeskyFieldSolver() override;

  FieldSolveReport apply(const ConstraintDiff& diff, const ConstraintSet& current) override;
  const Field& field() const override { return field_; }
  FieldMethod method() const override {
    return modify_ == solver::ModifyMethod::Refactorize ? FieldMethod::Refactorize : FieldMethod::Thesis;
  }

 private:
  Grid grid_;
  double omega_;
  solver::ModifyMethod modify_;
  SparseMatrix DtD_;
  Eigen::VectorXd weights_;  // ω² at constrained nodes
  Field targets_;
  Field field_;
  std::unique_ptr<solver::UpdatableCholesky> factor_;  // null until a constraint exists
};

}  // namespace lapis::hair_field
