#include "lapis/hair_field/cholesky_field_solver.h"

#include <chrono>
#include <string>
#include <vector>

#include "field_report.h"
#include "lapis/core/error.h"
#include "lapis/solver/updatable_cholesky.h"

namespace lapis::hair_field {

CholeskyFieldSolver::CholeskyFieldSolver(const Grid& grid, const FieldSolverOptions& options,
                                         solver::ModifyMethod modify)
    : grid_(grid), omega_(options.omega), modify_(modify) {
  const double bytes = estimate_cholesky_bytes(grid.num_nodes());
  if (bytes > options.memory_limit_bytes)
    throw ResourceLimit("hair_field::CholeskyFieldSolver(): the factor of " + std::to_string(grid.num_nodes()) +
                        " unknowns needs about " + std::to_string(static_cast<long long>(bytes / (1 << 20))) +
                        " MiB, more than the limit of " +
                        std::to_string(static_cast<long long>(options.memory_limit_bytes / (1 << 20))) + " MiB");
  const auto n = grid.num_nodes();
  weights_.setZero(n);
  DtD_ = normal_matrix(grid, weights_);
  targets_.setZero(n, 3);
  field_.setZero(n, 3);
}

CholeskyFieldSolver::~CholeskyFieldSolver() = default;

FieldSolveReport CholeskyFieldSolver::apply(const ConstraintDiff& diff, const ConstraintSet& current) {
  const auto t0 = std::chrono::steady_clock::now();
  const int n = static_cast<int>(field_.rows());
  FieldSolveReport rep = detail::start_report(method(), diff, current, n, "hair_field::CholeskyFieldSolver::apply()");
  // WᵀW has ω² per constrained node (§4.4.1).
  const double w = omega_ * omega_;
  std::vector<int> idx;
  std::vector<double> val;
  for (const Constraint& c : diff.added) {
    weights_[c.node] = w;
    targets_.row(c.node) = c.direction.transpose();
    idx.push_back(c.node);
    val.push_back(w);
  }
  for (int node : diff.removed) {
    weights_[node] = 0;
    targets_.row(node).setZero();
    idx.push_back(node);
    val.push_back(0.0);
  }
  for (const Constraint& c : diff.changed) targets_.row(c.node) = c.direction.transpose();

  if (current.empty()) {
    // DᵀD alone is singular (constants): drop the factor, the minimum-norm field is zero.
    factor_.reset();
    field_.setZero();
    rep.detail = "no constraints: zero field";
    rep.total_ms = detail::ms_since(t0);
    return rep;
  }
  if (!factor_) {
    factor_ = std::make_unique<solver::UpdatableCholesky>();
    factor_->set_method(modify_);
    factor_->compute(DtD_, weights_);
    rep.detail = "factorize";
  } else if (!idx.empty()) {
    // Added nodes become one update, removed ones one downdate (W₊ᵀW₊, W₋ᵀW₋, §4.4.2).
    const solver::ModifyReport m = factor_->set_diagonal_weights(idx, val);
    rep.detail = std::string(solver::to_string(m.method)) + " rank " + std::to_string(m.rank);
  } else {
    rep.detail = "right-hand side only";
  }
  rep.update_ms = detail::ms_since(t0);
  const auto t1 = std::chrono::steady_clock::now();
  const Eigen::MatrixXd b = weights_.asDiagonal() * targets_;
  field_ = factor_->solve(b);
  rep.solve_ms = detail::ms_since(t1);
  rep.total_ms = detail::ms_since(t0);
  return rep;
}

}  // namespace lapis::hair_field
