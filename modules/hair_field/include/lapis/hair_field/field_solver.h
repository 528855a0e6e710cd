// One interface over the ways the field's normal equations (DᵀD + WᵀW) T = WᵀW C are solved
// after a constraint edit (thesis §4.4.2): the thesis' Cholesky update/downdate, a fresh
// refactorization, and the multigrid fast path. Each edit returns a report naming the
// method that ran and what it cost.
#pragma once

#include <memory>
#include <string>

#include "lapis/hair_field/constraints.h"
#include "lapis/hair_field/grid.h"
#include "lapis/hair_field/grid_operators.h"

namespace lapis::hair_field {

enum class FieldMethod {
  Auto,         // chosen from the grid size and memory (see choose_field_method)
  Thesis,       // UpdatableCholesky: update + downdate per edit (§4.4.2); its cost model may
                // refactorize when that is predicted cheaper
  Refactorize,  // UpdatableCholesky forced to refactorize numerically on every edit
  Multigrid,    // matrix-free PCG with a Galerkin multigrid V-cycle, warm-started
};
const char* to_string(FieldMethod m);

struct FieldSolveReport {
  FieldMethod method = FieldMethod::Multigrid;  // what ran (never Auto)
  int added = 0, removed = 0, changed = 0;      // the diff applied
  double update_ms = 0;                         // modifying the factor / the multigrid operators
  double solve_ms = 0;                          // back-substitution / iterations
  double total_ms = 0;
  int iterations = 0;         // multigrid: PCG iterations (0 for direct paths)
  double error_estimate = 0;  // multigrid: estimated relative 2-norm error of the field
  std::string detail;         // e.g. "updown rank 240" or "refactorize"
};

class FieldSolver {
 public:
  virtual ~FieldSolver() = default;
  // Moves from the previous constraint set to `current`, where `diff` = diff(previous,
  // current). Afterwards field() minimizes the energy for `current`.
  virtual FieldSolveReport apply(const ConstraintDiff& diff, const ConstraintSet& current) = 0;
  virtual const Field& field() const = 0;
  virtual FieldMethod method() const = 0;
};

struct FieldSolverOptions {
  double omega = 100;  // constraint weight ω, thesis §4.4.1
  // Auto uses the thesis path while its factor (estimate_cholesky_bytes) stays under this
  // size (≈ 10K unknowns), the multigrid path beyond, where the multigrid solve is faster
  // (3–5× at 25K and 50K on the bundled head; docs/decisions.md) and its hierarchy is built
  // in a fraction of the factorization's time. At 1M the factor (~28 GiB) would not fit.
  double thesis_max_factor_bytes = 48.0 * (1 << 20);
  double memory_limit_bytes = kDefaultMemoryLimitBytes;
};

// The method Auto picks for grid.
FieldMethod choose_field_method(const Grid& grid, const FieldSolverOptions& options = {});

// Creates a solver for grid with no constraints (field zero). Throws ResourceLimit when the
// chosen method's memory estimate exceeds options.memory_limit_bytes.
std::unique_ptr<FieldSolver> make_field_solver(const Grid& grid, FieldMethod method,
                                               const FieldSolverOptions& options = {});

}  // namespace lapis::hair_field
