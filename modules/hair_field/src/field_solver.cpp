#include "lapis/hair_field/field_solver.h"

#include "lapis/core/error.h"
#include "lapis/hair_field/cholesky_field_solver.h"
#include "lapis/hair_field/multigrid_field_solver.h"

namespace lapis::hair_field {

const char* to_string(FieldMethod m) {
  switch (m) {
    case FieldMethod::Auto:
      return "auto";
    case FieldMethod::Thesis:
      return "thesis-updown";
    case FieldMethod::Refactorize:
      return "refactorize";
    case FieldMethod::Multigrid:
      return "multigrid";
  }
  return "?";
}

FieldMethod choose_field_method(const Grid& grid, const FieldSolverOptions& options) {
  return estimate_cholesky_bytes(grid.num_nodes()) <= options.thesis_max_factor_bytes ? FieldMethod::Thesis
                                                                                      : FieldMethod::Multigrid;
}

std::unique_ptr<FieldSolver> make_field_solver(const Grid& grid, FieldMethod method,
                                               const FieldSolverOptions& options) {
  if (method == FieldMethod::Auto) method = choose_field_method(grid, options);
  switch (method) {
    case FieldMethod::Thesis:
      return std::make_unique<CholeskyFieldSolver>(grid, options, solver::ModifyMethod::Auto);
    case FieldMethod::Refactorize:
      return std::make_unique<CholeskyFieldSolver>(grid, options, solver::ModifyMethod::Refactorize);
    default: {
      if (estimate_multigrid_bytes(grid.num_nodes()) > options.memory_limit_bytes)
        throw ResourceLimit("hair_field::make_field_solver(): the multigrid field of " +
                            std::to_string(grid.num_nodes()) + " unknowns exceeds the memory limit");
      MultigridFieldOptions mo;
      mo.field = options;
      return std::make_unique<MultigridFieldSolver>(grid, mo);
    }
  }
}

}  // namespace lapis::hair_field
