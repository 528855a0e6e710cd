// From a hairstyle document to its vector field and strands (thesis §4.4–4.6): the
// primitives' constraints, the field kept up to date incrementally as the document changes
// (only the constraint diff reaches the solver, §4.4.2), and the one-shot build that the
// command line and session replay use.
#pragma once

#include <memory>
#include <vector>

#include "lapis/hair_field/constraints.h"
#include "lapis/hair_field/field_solver.h"
#include "lapis/hair_field/grid.h"
#include "lapis/hair_sketch/document.h"
#include "lapis/hair_sketch/field_detail.h"
#include "lapis/hair_sketch/gravity_prior.h"
#include "lapis/hair_sketch/growth.h"
#include "lapis/hair_sketch/head.h"

namespace lapis::hair_sketch {

// The field's grid for a head and the document's settings (make_grid with settings.grid).
// It is the first step of every hairstyle, so it also checks, before any work, that the
// strands the settings ask for fit in memory (check_growth): ResourceLimit otherwise.
hair_field::Grid hairstyle_grid(const Head& head, const HairstyleSettings& settings);

// Sketch options matching the grid (curves resampled at its spacing) and the settings.
SketchOptions sketch_options(const hair_field::Grid& grid, const HairstyleSettings& settings);

// The constraints of one primitive / all of them merged (§4.5).
std::vector<hair_field::Constraint> primitive_constraints(const StylePrimitive& p, const hair_field::Grid& grid,
                                                          const Head& head);
hair_field::ConstraintSet style_constraints(const std::vector<StylePrimitive>& primitives, const hair_field::Grid& grid,
                                            const Head& head);

// Precompute once (the solver), then update per document revision: the new constraint set
// is diffed against the last one and only the diff is applied. Undo is just another update,
// whose diff is the inverse of the edit's.
//
// With field detail (field_detail.h), the solver solves for u = t − tᵉ: constraint targets are
// cᵢ − tᵉᵢ, and field() is tᵉ + u.
class StyleField {
 public:
  // Throws ResourceLimit when the method's memory estimate exceeds the solver's limit.
  StyleField(const Head& head, const hair_field::Grid& grid, hair_field::FieldMethod method,
             const hair_field::FieldSolverOptions& options = {}, const FieldDetailOptions& detail = {},
             const GravityPriorOptions& prior = {});
  // Re-solves for primitives (plus `extra` constraints, e.g. scalp avoidance, and the gravity
  // prior where neither constrains a node).
  hair_field::FieldSolveReport update(const std::vector<StylePrimitive>& primitives,
                                      const std::vector<hair_field::Constraint>& extra = {});
  const hair_field::Field& field() const { return example_.size() ? detailed_ : solver_->field(); }
  const hair_field::ConstraintSet& constraints() const { return current_; }
  const hair_field::Grid& grid() const { return grid_; }
  hair_field::FieldMethod method() const { return solver_->method(); }

 private:
  const Head* head_;
  hair_field::Grid grid_;
  std::unique_ptr<hair_field::FieldSolver> solver_;
  hair_field::ConstraintSet current_;          // as the solver sees them (minus tᵉ with field detail)
  hair_field::Field example_;                  // tᵉ; empty without field detail
  hair_field::Field detailed_;                 // tᵉ + u
  std::vector<hair_field::Constraint> prior_;  // gravity_prior.h; empty when off
  int prior_clearance_ = 0;
};

struct HairstyleResult {
  hair_field::Grid grid;
  hair_field::Field field;
  Strands strands;
  int constraints = 0;
  int penetrating_segments = 0;
  std::vector<hair_field::FieldSolveReport> solves;  // the style solve, then the avoidance solve
  double grid_ms = 0, solve_ms = 0, growth_ms = 0, detail_ms = 0, penetration_ms = 0;
  double clearance_ms = 0;  // sampling the head's distance (HeadClearance), for growth and detail
};

// Solves the document's field from scratch (style, then scalp avoidance if enabled), grows
// settings.roots strands, applies the details and counts penetrating segments (after detail). Deterministic: the same
// document and head give bit-identical strands.
HairstyleResult build_hairstyle(const Hairstyle& style, const Head& head);

}  // namespace lapis::hair_sketch
