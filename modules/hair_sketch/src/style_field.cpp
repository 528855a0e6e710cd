// The document's field and strands: incremental updates and the one-shot build.
#include "lapis/hair_sketch/style_field.h"

#include <chrono>
#include <memory>

#include "lapis/hair_sketch/scalp_avoidance.h"
#include "lapis/hair_sketch/symmetry.h"

namespace lapis::hair_sketch {
using hair_field::Constraint;
using hair_field::ConstraintSet;
using hair_field::diff;
using hair_field::FieldMethod;
using hair_field::FieldSolveReport;
using hair_field::FieldSolverOptions;
using hair_field::Grid;
using hair_field::make_field_solver;
using hair_field::make_grid;

namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

Grid hairstyle_grid(const Head& head, const HairstyleSettings& settings) {
  check_growth(settings.roots.count, settings.growth, "hair_sketch::hairstyle_grid()");
  return make_grid(head.box, settings.grid);
}

SketchOptions sketch_options(const Grid& grid, const HairstyleSettings& settings) {
  SketchOptions o = settings.sketch;
  o.spacing = grid.spacing;
  return o;
}

std::vector<Constraint> primitive_constraints(const StylePrimitive& p, const Grid& grid, const Head& head) {
  if (p.mirrored) {  // the primitive's, then its twin's (symmetry.h)
    StylePrimitive own = p;
    own.mirrored = false;
    std::vector<Constraint> out = primitive_constraints(own, grid, head);
    const std::vector<Constraint> twin = primitive_constraints(mirror_image(own, head.center.x()), grid, head);
    out.insert(out.end(), twin.begin(), twin.end());
    return out;
  }
  return std::visit(
      [&](const auto& shape) -> std::vector<Constraint> {
        using T = std::decay_t<decltype(shape)>;
        if constexpr (std::is_same_v<T, DividingCurve>)
          return shape.constraints(grid, head);
        else
          return shape.constraints(grid);
      },
      p.shape);
}

ConstraintSet style_constraints(const std::vector<StylePrimitive>& primitives, const Grid& grid, const Head& head) {
  std::vector<std::vector<Constraint>> groups;
  for (const auto& p : primitives) groups.push_back(primitive_constraints(p, grid, head));
  return ConstraintSet::merge(groups);
}

StyleField::StyleField(const Head& head, const Grid& grid, FieldMethod method, const FieldSolverOptions& options,
                       const FieldDetailOptions& detail, const GravityPriorOptions& prior)
    : head_(&head),
      grid_(grid),
      solver_(make_field_solver(grid, method, options)),
      prior_(gravity_prior_constraints(head, grid, prior)),
      prior_clearance_(prior.clearance) {
  if (detail.amplitude > 0) {
    example_ = wavy_example_field(grid, head.center, detail);
    detailed_ = example_;
  } else {
    wavy_example_field(grid, head.center, detail);  // checks the options
  }
}

FieldSolveReport StyleField::update(const std::vector<StylePrimitive>& primitives,
                                    const std::vector<Constraint>& extra) {
  std::vector<std::vector<Constraint>> groups;
  for (const auto& p : primitives) groups.push_back(primitive_constraints(p, grid_, *head_));
  const std::vector<Constraint> prior =
      prior_.empty() ? prior_ : prior_away_from(prior_, ConstraintSet::merge(groups), grid_, prior_clearance_);
  if (!extra.empty()) groups.push_back(extra);
  ConstraintSet next = with_prior(ConstraintSet::merge(groups), prior);
  if (example_.size()) {  // u = t − tᵉ meets cᵢ − tᵉᵢ (field_detail.h)
    std::vector<std::vector<Constraint>> shifted{next.items()};
    for (Constraint& c : shifted.front()) c.direction -= example_.row(c.node).transpose();
    next = ConstraintSet::merge(shifted);
  }
  const FieldSolveReport report = solver_->apply(diff(current_, next), next);
  current_ = std::move(next);
  if (example_.size()) detailed_ = example_ + solver_->field();
  return report;
}

HairstyleResult build_hairstyle(const Hairstyle& style, const Head& head) {
  const HairstyleSettings& s = style.settings;
  HairstyleResult r;
  auto t0 = std::chrono::steady_clock::now();
  r.grid = hairstyle_grid(head, s);
  StyleField field(head, r.grid, s.field_method, s.field, s.field_detail, s.gravity_prior);
  r.grid_ms = ms_since(t0);
  t0 = std::chrono::steady_clock::now();
  r.solves.push_back(field.update(style.primitives));
  if (s.scalp_avoidance && !field.constraints().empty())
    r.solves.push_back(field.update(style.primitives, scalp_avoidance_constraints(r.grid, field.field(), head)));
  r.solve_ms = ms_since(t0);
  r.field = field.field();
  r.constraints = field.constraints().size();
  t0 = std::chrono::steady_clock::now();
  const std::vector<Eigen::Vector3d> roots = sample_roots(head, s.roots);
  std::unique_ptr<HeadClearance> clearance;
  if (s.growth.keep_outside_head || !style.details.empty()) {
    clearance = std::make_unique<HeadClearance>(head, r.grid);
    r.clearance_ms = ms_since(t0);
    t0 = std::chrono::steady_clock::now();
  }
  r.strands = grow_strands(SampledField(r.grid, r.field, s.growth.keep_outside_head ? clearance.get() : nullptr), roots,
                           s.growth);
  r.growth_ms = ms_since(t0);
  if (!style.details.empty()) {
    t0 = std::chrono::steady_clock::now();
    for (const auto& d : style.details) check_detail(d, head.mesh.num_vertices(), "hair_sketch::build_hairstyle()");
    r.strands = apply_strand_detail(r.strands, style.details,
                                    detail_context(head, roots, clearance.get(), s.growth.head_clearance));
    r.detail_ms = ms_since(t0);
  }
  t0 = std::chrono::steady_clock::now();
  r.penetrating_segments = count_penetrating_segments(r.strands, head);
  r.penetration_ms = ms_since(t0);
  return r;
}

}  // namespace lapis::hair_sketch
