#include "lapis/hair_field/multigrid_field_solver.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "field_report.h"
#include "grid_stencil.h"
#include "lapis/core/error.h"
#include "local_relaxation.h"
#include "multigrid_hierarchy.h"

namespace lapis::hair_field {

namespace {

using detail::parallel_nodes;  // element-wise passes run on one thread below this many nodes

// Applies the diff to the weights (ω² at constrained nodes) and targets; returns the
// changes of the normal matrix' diagonal it makes.
std::vector<std::pair<int, double>> apply_to_weights(const ConstraintDiff& diff, double w, Eigen::VectorXd& weights,
                                                     Field& targets) {
  std::vector<std::pair<int, double>> changes;
  changes.reserve(diff.added.size() + diff.removed.size());
  for (const Constraint& c : diff.added) {
    changes.emplace_back(c.node, w - weights[c.node]);
    weights[c.node] = w;
    targets.row(c.node) = c.direction.transpose();
  }
  for (int node : diff.removed) {
    changes.emplace_back(node, -weights[node]);
    weights[node] = 0;
    targets.row(node).setZero();
  }
  for (const Constraint& c : diff.changed) targets.row(c.node) = c.direction.transpose();
  return changes;
}

// The report's detail, e.g. "pcg+mg 5 levels (corrections per coarse visit: 4, 2), 12
// iterations": the W-cycle's corrections per visit of levels 1, 2, ... (those above the
// coarsest but one, which always make one).
std::string solve_detail(const detail::MultigridHierarchy& mg, int relaxed, int iterations) {
  std::string corrections;
  bool w_cycle = false;
  for (int l = 1; l + 2 < mg.levels(); ++l) {
    corrections += (l > 1 ? ", " : "") + std::to_string(mg.corrections(l));
    w_cycle = w_cycle || mg.corrections(l) > 1;
  }
  return "pcg+mg " + std::to_string(mg.levels()) + " levels" +
         (w_cycle ? " (corrections per coarse visit: " + corrections + ")" : "") + ", " +
         (relaxed > 0 ? std::to_string(relaxed) + " nodes relaxed near the edit, " : "") + std::to_string(iterations) +
         " iterations";
}

}  // namespace

// The iteration's vectors, allocated with the solver: an iteration allocates nothing (a
// fresh 50K×3 temporary per vector operation cost page faults in every iteration). Its
// steps fuse the vector operations of an iteration into as few passes over the field as
// the dot products allow (each must complete before the update that uses it), each pass
// one parallel loop.
struct MultigridFieldSolver::Work {
  Field x, r, p, q;
  detail::FieldF rf, zf;  // the cycle's residual and correction, in its precision
  detail::StencilScratch<double> buffers;
  std::vector<double> line_dots;  // per thread: p·q's three column sums, 8 doubles apart
  std::vector<char> mark;         // nodes_near()'s scratch, one per node

  explicit Work(int n) : x(n, 3), r(n, 3), p(n, 3), q(n, 3), rf(n, 3), zf(n, 3), mark(static_cast<size_t>(n), 0) {}

  int nodes() const { return static_cast<int>(x.rows()); }

  // r = b − A x with the exact double operator, b = WᵀW c formed on the fly, and r's copy
  // in the cycle's precision; returns ‖r‖².
  double residual(const Grid& grid, const double* wt, const double* tg) {
    double* rr = r.data();
    detail::normal_operator_visit(grid.dims, wt, x.data(), buffers,
                                  [&](std::ptrdiff_t f0, std::ptrdiff_t len, const double* v) {
                                    for (std::ptrdiff_t f = f0; f < f0 + len; ++f)
                                      rr[f] = wt[f / 3] * tg[f] - v[f - f0];
                                  });
    const int n = nodes();
    detail::Real* rfp = rf.data();
    double rnorm2 = 0;
#pragma omp parallel for schedule(static) reduction(+ : rnorm2) if (n > parallel_nodes)
    for (int i = 0; i < 3 * n; ++i) {
      rfp[i] = static_cast<detail::Real>(rr[i]);
      rnorm2 += rr[i] * rr[i];
    }
    return rnorm2;
  }

  // p = z, the first direction.
  void first_direction() {
    const int n = nodes();
    double* pp = p.data();
    const detail::Real* z = zf.data();
#pragma omp parallel for schedule(static) if (n > parallel_nodes)
    for (int i = 0; i < 3 * n; ++i) pp[i] = static_cast<double>(z[i]);
  }

  // q = A p, and the column dots p·q on each line as it is written (per-thread partial
  // sums, a cache line apart).
  void product(const Grid& grid, const double* wt, double pq[3]) {
    double* qq = q.data();
    const double* pp = p.data();
    line_dots.assign(8 * static_cast<size_t>(std::max(1, omp_get_max_threads())), 0.0);
    detail::normal_operator_visit(grid.dims, wt, pp, buffers,
                                  [&](std::ptrdiff_t f0, std::ptrdiff_t len, const double* v) {
                                    double* dots = line_dots.data() + 8 * omp_get_thread_num();
                                    double* ql = qq + f0;
                                    const double* pl = pp + f0;
                                    for (std::ptrdiff_t f = 0; f < len; f += 3) {
                                      for (int c = 0; c < 3; ++c) {
                                        ql[f + c] = v[f + c];
                                        dots[c] += pl[f + c] * v[f + c];
                                      }
                                    }
                                  });
    pq[0] = pq[1] = pq[2] = 0;
    for (size_t t = 0; t < line_dots.size(); t += 8)
      for (int c = 0; c < 3; ++c) pq[c] += line_dots[t + c];
  }

  // x += α p and r −= α q, with the cycle's copy of r; step2 = ‖α p‖², x2 = ‖x‖².
  void advance(const double alpha[3], double& step2, double& x2) {
    const int n = nodes();
    double* xx = x.data();
    double* rr = r.data();
    const double* pp = p.data();
    const double* qq = q.data();
    detail::Real* rfp = rf.data();
    double s2 = 0, xn2 = 0;
#pragma omp parallel for schedule(static) reduction(+ : s2, xn2) if (n > parallel_nodes)
    for (int i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) {
        const std::ptrdiff_t f = 3 * static_cast<std::ptrdiff_t>(i) + c;
        const double step = alpha[c] * pp[f];
        xx[f] += step;
        rr[f] -= alpha[c] * qq[f];
        rfp[f] = static_cast<detail::Real>(rr[f]);
        s2 += step * step;
        xn2 += xx[f] * xx[f];
      }
    step2 = s2;
    x2 = xn2;
  }

  // p = z + β p.
  void next_direction(const double beta[3]) {
    const int n = nodes();
    double* pp = p.data();
    const detail::Real* z = zf.data();
#pragma omp parallel for schedule(static) if (n > parallel_nodes)
    for (int i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) {
        const std::ptrdiff_t f = 3 * static_cast<std::ptrdiff_t>(i) + c;
        pp[f] = static_cast<double>(z[f]) + beta[c] * pp[f];
      }
  }
};

MultigridFieldSolver::MultigridFieldSolver(const Grid& grid, MultigridFieldOptions options)
    : grid_(grid), opt_(options) {
  const auto n = grid.num_nodes();
  if (n < 8 || n > std::numeric_limits<int>::max() / 32)
    throw InvalidArgument("hair_field::MultigridFieldSolver(): grid of " + std::to_string(n) +
                          " nodes is out of range");
  weights_.setZero(n);
  targets_.setZero(n, 3);
  field_.setZero(n, 3);
  detail::MultigridOptions mo;
  mo.smoothing_degree = opt_.smoothing_degree;
  mo.cycle_index = opt_.cycle_index;
  mo.coarse_cycle_index = opt_.coarse_cycle_index;
  mo.smoothing_range = opt_.smoothing_range;
  mo.coarsest_nodes = opt_.coarsest_nodes;
  mo.cubic = opt_.cubic_prolongation;
  mg_ = std::make_unique<detail::MultigridHierarchy>(grid_, weights_, mo);
  work_ = std::make_unique<Work>(static_cast<int>(n));
}

MultigridFieldSolver::~MultigridFieldSolver() = default;

int MultigridFieldSolver::levels() const { return mg_->levels(); }

int MultigridFieldSolver::relax_near_edit(const ConstraintDiff& diff) {
  if (opt_.relax_sweeps <= 0 || opt_.relax_radius < 0) return 0;
  std::vector<int> seeds;
  seeds.reserve(diff.added.size() + diff.removed.size() + diff.changed.size());
  for (const Constraint& c : diff.added) seeds.push_back(c.node);
  seeds.insert(seeds.end(), diff.removed.begin(), diff.removed.end());
  for (const Constraint& c : diff.changed) seeds.push_back(c.node);
  if (seeds.empty()) return 0;
  const std::vector<int> nodes = detail::nodes_near(grid_.dims, seeds, opt_.relax_radius, work_->mark);
  // Only where it costs a small part of one iteration (a whole new style relaxes nothing).
  if (static_cast<double>(nodes.size()) * opt_.relax_sweeps > opt_.relax_budget * field_.rows()) return 0;
  detail::gauss_seidel(grid_.dims, weights_.data(), targets_.data(), nodes, opt_.relax_sweeps, work_->x.data());
  return static_cast<int>(nodes.size());
}

FieldSolveReport MultigridFieldSolver::apply(const ConstraintDiff& diff, const ConstraintSet& current) {
  const auto t0 = std::chrono::steady_clock::now();
  const int n = static_cast<int>(field_.rows());
  FieldSolveReport rep =
      detail::start_report(FieldMethod::Multigrid, diff, current, n, "hair_field::MultigridFieldSolver::apply()");
  const auto changes = apply_to_weights(diff, opt_.field.omega * opt_.field.omega, weights_, targets_);
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

  work_->x = field_;
  const int relaxed = relax_near_edit(diff);
  const Pcg pcg = solve_from_warm_start(current);
  if (!pcg.converged)
    throw SolverFailure("hair_field::MultigridFieldSolver::apply(): no convergence in " +
                        std::to_string(opt_.max_iterations) + " iterations (estimated error " +
                        std::to_string(pcg.error_estimate) + ")");
  field_.swap(work_->x);
  rep.iterations = pcg.iterations;
  rep.error_estimate = pcg.error_estimate;
  rep.detail = solve_detail(*mg_, relaxed, pcg.iterations);
  rep.solve_ms = detail::ms_since(t1);
  rep.total_ms = detail::ms_since(t0);
  return rep;
}

MultigridFieldSolver::Pcg MultigridFieldSolver::solve_from_warm_start(const ConstraintSet& current) {
  Work& wk = *work_;
  const double* wt = weights_.data();
  const double rnorm2 = wk.residual(grid_, wt, targets_.data());
  double bnorm2 = 0;  // b is zero off the constraints
  for (const Constraint& c : current.items()) bnorm2 += wt[c.node] * wt[c.node] * targets_.row(c.node).squaredNorm();
  const double bnorm = std::sqrt(bnorm2);
  // The column dots r·z come from the cycle itself, formed as its last step writes z.
  double dots[3];
  mg_->apply(wk.rf, wk.zf, wk.r.data(), dots);
  Eigen::RowVector3d rz(dots[0], dots[1], dots[2]);
  wk.first_direction();
  Pcg out;
  double prev_step = 0;
  int it = 0;
  out.converged = std::sqrt(rnorm2) <= 1e-15 * std::max(bnorm, 1e-300);
  for (; !out.converged && it < opt_.max_iterations; ++it) {
    double pq[3];
    wk.product(grid_, wt, pq);
    double alpha[3];
    for (int c = 0; c < 3; ++c) alpha[c] = pq[c] > 0 ? rz[c] / pq[c] : 0.0;
    double step2 = 0, x2 = 0;
    wk.advance(alpha, step2, x2);
    // With a uniform preconditioned spectrum the steps shrink geometrically at rate ρ;
    // the error left is then about step·ρ/(1−ρ). ρ is taken pessimistically (max of the
    // last ratio and 0.5) so one lucky short step cannot stop the iteration.
    const double step_norm = std::sqrt(step2);
    const double rho = it == 0 ? 0.9 : std::clamp(step_norm / std::max(prev_step, 1e-300), 0.5, 0.95);
    prev_step = step_norm;
    out.error_estimate = step_norm * rho / (1 - rho) / std::max(std::sqrt(x2), 1e-300);
    // Not before the third step: the first ratios are not yet the settled rate (the estimate
    // at the second step was measured at half the true error).
    if (it >= 2 && out.error_estimate <= opt_.tolerance) {
      out.converged = true;
      ++it;
      break;
    }
    mg_->apply(wk.rf, wk.zf, wk.r.data(), dots);
    const Eigen::RowVector3d rz_new(dots[0], dots[1], dots[2]);
    double beta[3];
    for (int c = 0; c < 3; ++c) beta[c] = rz[c] > 0 ? rz_new[c] / rz[c] : 0.0;
    wk.next_direction(beta);
    rz = rz_new;
  }
  out.iterations = it;
  return out;
}

}  // namespace lapis::hair_field
