#include "lapis/hair_sketch/multigrid_field_solver.h"

#include <chrono>
#include <cmath>
#include <string>

#include "field_report.h"
#include "lapis/core/error.h"
#include "multigrid_hierarchy.h"

namespace lapis::hair_sketch {
namespace {

Eigen::RowVector3d column_dots(const Field& a, const Field& b) {
  return (a.array() * b.array()).colwise().sum();
}

}  // namespace

MultigridFieldSolver::MultigridFieldSolver(const Grid& grid, MultigridFieldOptions options)
    : grid_(grid), opt_(options) {
  const auto n = grid.num_nodes();
  if (n < 8 || n > std::numeric_limits<int>::max() / 32)
    throw InvalidArgument("hair_sketch::MultigridFieldSolver(): grid of " + std::to_string(n) +
                          " nodes is out of range");
  weights_.setZero(n);
  targets_.setZero(n, 3);
  field_.setZero(n, 3);
  detail::MultigridOptions mo;
  mo.smoothing_degree = opt_.smoothing_degree;
  mo.cycle_index = opt_.cycle_index;
  mo.smoothing_range = opt_.smoothing_range;
  mo.coarsest_nodes = opt_.coarsest_nodes;
  mo.cubic = opt_.cubic_prolongation;
  mg_ = std::make_unique<detail::MultigridHierarchy>(grid_, weights_, mo);
}

MultigridFieldSolver::~MultigridFieldSolver() = default;

int MultigridFieldSolver::levels() const { return mg_->levels(); }

FieldSolveReport MultigridFieldSolver::apply(const ConstraintDiff& diff,
                                             const ConstraintSet& current) {
  const auto t0 = std::chrono::steady_clock::now();
  const int n = static_cast<int>(field_.rows());
  FieldSolveReport rep = detail::start_report(FieldMethod::Multigrid, diff, current, n,
                                              "hair_sketch::MultigridFieldSolver::apply()");
  const double w = opt_.omega * opt_.omega;
  std::vector<std::pair<int, double>> changes;
  changes.reserve(diff.added.size() + diff.removed.size());
  for (const Constraint& c : diff.added) {
    changes.emplace_back(c.node, w - weights_[c.node]);
    weights_[c.node] = w;
    targets_.row(c.node) = c.direction.transpose();
  }
  for (int node : diff.removed) {
    changes.emplace_back(node, -weights_[node]);
    weights_[node] = 0;
    targets_.row(node).setZero();
  }
  for (const Constraint& c : diff.changed) targets_.row(c.node) = c.direction.transpose();
  if (!changes.empty()) mg_->add_to_diagonal(changes);
  rep.update_ms = detail::ms_since(t0);
  const auto t1 = std::chrono::steady_clock::now();

  if (current.empty()) {
    // DᵀD alone is singular (constants); with nothing constrained the minimum-norm
    // minimizer is the zero field.
    field_.setZero();
    rep.detail = "no constraints: zero field";
    rep.solve_ms = detail::ms_since(t1);
    rep.total_ms = detail::ms_since(t0);
    return rep;
  }

  // b = WᵀW c; r = b − A x with the exact double operator.
  const Field b = weights_.asDiagonal() * targets_;
  Field x = field_, Ax, r, p, q;
  apply_normal_operator(grid_, weights_, x, Ax);
  r = b - Ax;
  const double bnorm = b.norm();
  detail::FieldF zf;
  mg_->apply(r.cast<detail::Real>(), zf);
  Field z = zf.cast<double>();
  p = z;
  Eigen::RowVector3d rz = column_dots(r, z);
  double prev_step = 0, est = 0;
  int it = 0;
  bool converged = r.norm() <= 1e-15 * std::max(bnorm, 1e-300);
  for (; !converged && it < opt_.max_iterations; ++it) {
    apply_normal_operator(grid_, weights_, p, q);
    const Eigen::RowVector3d pq = column_dots(p, q);
    Eigen::RowVector3d alpha;
    for (int c = 0; c < 3; ++c) alpha[c] = pq[c] > 0 ? rz[c] / pq[c] : 0.0;
    const Field step = p * alpha.asDiagonal();
    x += step;
    r -= q * alpha.asDiagonal();
    // With a uniform preconditioned spectrum the steps shrink geometrically at rate ρ;
    // the error left is then about step·ρ/(1−ρ). ρ is taken pessimistically (max of the
    // last ratio and 0.5) so one lucky short step cannot stop the iteration.
    const double step_norm = step.norm();
    const double rho = it == 0 ? 0.9 : std::clamp(step_norm / std::max(prev_step, 1e-300), 0.5, 0.95);
    prev_step = step_norm;
    est = step_norm * rho / (1 - rho) / std::max(x.norm(), 1e-300);
    if (it >= 1 && est <= opt_.tolerance) {
      converged = true;
      ++it;
      break;
    }
    mg_->apply(r.cast<detail::Real>(), zf);
    z = zf.cast<double>();
    const Eigen::RowVector3d rz_new = column_dots(r, z);
    for (int c = 0; c < 3; ++c) {
      const double beta = rz[c] > 0 ? rz_new[c] / rz[c] : 0.0;
      p.col(c) = z.col(c) + beta * p.col(c);
    }
    rz = rz_new;
  }
  if (!converged)
    throw SolverFailure("hair_sketch::MultigridFieldSolver::apply(): no convergence in " +
                        std::to_string(opt_.max_iterations) + " iterations (estimated error " +
                        std::to_string(est) + ")");
  field_ = std::move(x);
  rep.iterations = it;
  rep.error_estimate = est;
  rep.detail = "pcg+mg " + std::to_string(mg_->levels()) + " levels, " + std::to_string(it) +
               " iterations";
  rep.solve_ms = detail::ms_since(t1);
  rep.total_ms = detail::ms_since(t0);
  return rep;
}

}  // namespace lapis::hair_sketch
