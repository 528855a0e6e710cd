// Shared setup of the hair_sketch tests: the bundled head, a small grid over it (small
// enough for a direct factorization), solving a style and growing strands.
#pragma once

#include <memory>
#include <vector>

#include "lapis/hair_field/constraints.h"
#include "lapis/hair_field/field_solver.h"
#include "lapis/hair_field/grid.h"
#include "lapis/hair_sketch/growth.h"
#include "lapis/hair_sketch/head.h"

namespace hair_test {

using namespace lapis::hair_sketch;
using namespace lapis::hair_field;

// Loaded once: building the BVH for every test case costs more than the cases.
inline const Head& bundled_head() {
  static const Head head = load_bundled_head(LAPIS_SOURCE_DIR);
  return head;
}

inline Grid small_grid(double unknowns = 12000) {
  GridOptions o;
  o.target_unknowns = unknowns;
  return make_grid(bundled_head().box, o);
}

// The exact minimizer for a constraint set, by the thesis path (one factorization).
inline Field solve_exact(const Grid& grid, const ConstraintSet& set) {
  auto s = make_field_solver(grid, FieldMethod::Thesis);
  s->apply(diff(ConstraintSet(), set), set);
  return s->field();
}

inline double cosine(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return a.dot(b) / (a.norm() * b.norm() + 1e-300);
}

}  // namespace hair_test
