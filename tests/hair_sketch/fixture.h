// Shared setup of the hair_sketch tests: the bundled head, a small grid over it (small
// enough for a direct factorization), solving a style and growing strands.
#pragma once

#include <cmath>
#include <memory>
#include <vector>

#include "lapis/hair_field/constraints.h"
#include "lapis/hair_field/field_solver.h"
#include "lapis/hair_field/grid.h"
#include "lapis/hair_sketch/growth.h"
#include "lapis/hair_sketch/head.h"
#include "lapis/hair_sketch/ponytail.h"

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

// Strands that enter the ponytail's annulus (within R2 = outer_ratio · r of C1's centre) and,
// of those, the ones that then cross C1's plane within its radius (+ half a grid spacing):
// the hair the tail should gather and the hair it does (thesis §4.5). Strands guided there
// are funnelled before they reach C1's plane, so the thin slab of the centripetal constraints
// itself is rarely visited.
struct TailPassage {
  int entered = 0, through = 0;
};
inline TailPassage strands_entering_tail(const Strands& st, const Ponytail& tail, double spacing) {
  const Ponytail::Section sec = tail.first_section();
  TailPassage out;
  for (int s = 0; s < st.count(); ++s) {
    bool in_annulus = false, passed = false;
    for (int i = st.offsets[s]; i < st.offsets[s + 1]; ++i) {
      const Eigen::Vector3d q = st.points[i].cast<double>() - sec.center;
      const double h = q.dot(sec.normal), rho = (q - h * sec.normal).norm();
      if (std::hypot(h, rho) <= tail.outer_ratio * sec.radius) in_annulus = true;
      if (in_annulus && i + 1 < st.offsets[s + 1]) {
        const Eigen::Vector3d q2 = st.points[i + 1].cast<double>() - sec.center;
        const double h2 = q2.dot(sec.normal);
        if ((h <= 0) != (h2 <= 0) || h2 == 0) {
          const double t = h / (h - h2);
          const Eigen::Vector3d x = q + t * (q2 - q);
          if ((x - x.dot(sec.normal) * sec.normal).norm() <= sec.radius + 0.5 * spacing) passed = true;
        }
      }
    }
    out.entered += in_annulus;
    out.through += in_annulus && passed;
  }
  return out;
}

}  // namespace hair_test
