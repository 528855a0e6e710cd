// The fast field path: conjugate gradients on the exact normal equations (applied
// matrix-free in double), preconditioned by one Galerkin multigrid cycle in single
// precision, warm-started from the previous field. Plain CG stalls on this system (the
// bi-Laplacian plus ω² = 10⁴ diagonal entries: a small residual is not a small error); the
// multigrid preconditioner makes the spectrum uniform, so the iteration's step sizes
// bound the remaining error and the stop test is on the estimated error, not the residual.
#pragma once

#include <memory>

#include "lapis/hair_field/field_solver.h"

namespace lapis::hair_field {

namespace detail {
class MultigridHierarchy;
}

struct MultigridFieldOptions {
  FieldSolverOptions field;  // the energy's ω (thesis §4.4.1) and the memory limit
  // Stop when the estimated relative 2-norm error of the field is below this. The field must
  // be within 1e-6; against direct solves the estimate was 1.1–3.3× the true error once the
  // iteration had settled, and the factor 2 here is margin on top of that.
  double tolerance = 5e-7;
  int max_iterations = 200;
  // The cycle: Chebyshev smoothing of degree 2 before and after each coarse correction, one
  // coarse correction per cycle on the finest level and several per visit of each coarser
  // one. The V-cycle's coarse correction weakens with depth, and a strong one lets the costly
  // fine level smooth less. The corrections after the first cost one product on the coarser
  // level only (multigrid_cycle.cpp), so four are cheap where the hierarchy is deep: at
  // 250K and 1M four corrections save 3–4 iterations over two, at 50K (4 levels) none, hence
  // the automatic choice. The measurements, and the variants that were slower (degree 1, a
  // W-cycle on the finest level too), are in docs/decisions.md.
  int smoothing_degree = 2;         // Chebyshev degree per pre/post smoothing
  int cycle_index = 1;              // coarse corrections per cycle on the finest level
  int coarse_cycle_index = 0;       // ... per visit of each coarser level (1: V-cycle; 0: 4 if
                                    // the hierarchy has 5 or more levels, else 2, and at most
                                    // 2 into a level small enough to run on one thread, where
                                    // the other thread waits: the same iterations, faster)
  int coarsest_nodes = 500;         // dense LDLᵀ at or below this many nodes
  bool cubic_prolongation = false;  // cubic measured worse (70 vs 41 iterations)
  double smoothing_range = 0.12;    // Chebyshev smooths λ(D⁻¹A) in [range·λmax, λmax]
  // The warm start is first relaxed by Gauss–Seidel sweeps over the nodes within this many
  // nodes of a changed constraint (local_relaxation.h: after an edit most of the previous
  // field's error is there, and it saves an iteration at 250K and 1M), when the sweeps update
  // at most relax_budget × (grid nodes) nodes; 0 sweeps: never.
  int relax_radius = 3;
  int relax_sweeps = 15;
  double relax_budget = 0.5;
};

class MultigridFieldSolver final : public FieldSolver {
 public:
  explicit MultigridFieldSolver(const Grid& grid, MultigridFieldOptions options = {});
  ~MultigridFieldSolver() override;

  // Throws SolverFailure when the iteration does not reach the tolerance in
  // max_iterations; the constraints are then applied and field() keeps the previous field.
  FieldSolveReport apply(const ConstraintDiff& diff, const ConstraintSet& current) override;
  const Field& field() const override { return field_; }
  FieldMethod method() const override { return FieldMethod::Multigrid; }

  int levels() const;

 private:
  Grid grid_;
  MultigridFieldOptions opt_;
  Eigen::VectorXd weights_;  // ω² at constrained nodes
  Field targets_;            // c_i at constrained nodes, 0 elsewhere
  Field field_;
  std::unique_ptr<detail::MultigridHierarchy> mg_;
  // Relaxes the warm start near the diff's nodes; returns how many nodes it relaxed.
  int relax_near_edit(const ConstraintDiff& diff);
  // Preconditioned CG from the warm start in work_->x for the current weights and targets.
  struct Pcg {
    int iterations = 0;
    double error_estimate = 0;
    bool converged = false;
  };
  Pcg solve_from_warm_start(const ConstraintSet& current);
  struct Work;  // the iteration's vectors, kept between solves
  std::unique_ptr<Work> work_;
};

}  // namespace lapis::hair_field
