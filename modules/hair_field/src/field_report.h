// What every field solver does first on an edit: check the constraint nodes against the
// grid and start the report with the diff's counts.
#pragma once

#include <chrono>
#include <string>

#include "lapis/core/error.h"
#include "lapis/hair_field/field_solver.h"

namespace lapis::hair_field::detail {

inline double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// Throws InvalidArgument "<who>: constraint node k outside the grid of n nodes".
inline FieldSolveReport start_report(FieldMethod method, const ConstraintDiff& diff, const ConstraintSet& current,
                                     int n, const char* who) {
  if (current.max_node() >= n)
    throw InvalidArgument(std::string(who) + ": constraint node " + std::to_string(current.max_node()) +
                          " outside the grid of " + std::to_string(n) + " nodes");
  FieldSolveReport rep;
  rep.method = method;
  rep.added = static_cast<int>(diff.added.size());
  rep.removed = static_cast<int>(diff.removed.size());
  rep.changed = static_cast<int>(diff.changed.size());
  return rep;
}

}  // namespace lapis::hair_field::detail
