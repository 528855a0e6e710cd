// The interactive loop of thesis ch. 4 as one object: a head, a grid and a field solver set
// up once; then, per document revision, the primitives' constraints are diffed against the
// previous ones and only the diff reaches the solver (§4.4.2), scalp avoidance is re-derived
// from the new field (§4.6), and the strands regrow from fixed roots (§4.6). Strand detail
// (§4.7) is applied to the grown strands last; an edit of the details alone reapplies them to
// the strands already grown, without a solve or a regrowth. The sketching app runs update() on a worker thread;
// build_hairstyle() is the one-shot equivalent.
#pragma once

#include <memory>
#include <vector>

#include "lapis/hair_sketch/document.h"
#include "lapis/hair_sketch/growth.h"
#include "lapis/hair_sketch/head.h"
#include "lapis/hair_sketch/scalp_avoidance.h"
#include "lapis/hair_sketch/strand_detail.h"
#include "lapis/hair_sketch/style_field.h"

namespace lapis::hair_sketch {

struct LiveUpdate {
  Strands strands;
  std::vector<hair_field::FieldSolveReport> solves;  // the style solve, then the avoidance solve
  int constraints = 0;
  double solve_ms = 0;      // constraint diff + field update(s)
  double avoidance_ms = 0;  // of solve_ms: finding scalp avoidance's constraints (§4.6)
  double growth_ms = 0;     // regrowing every strand
  double detail_ms = 0;     // applying the strand details
  bool regrown = false;     // false: the primitives were unchanged, only the details were reapplied
  double total_ms = 0;
};

class LiveHairstyle {
 public:
  // Builds the grid, the solver and the roots for `settings`. The head must outlive this.
  // Throws ResourceLimit when the grid's solvers (two with scalp avoidance) would not fit in
  // memory.
  LiveHairstyle(const Head& head, const HairstyleSettings& settings);

  // Brings the field and the strands up to date with `primitives`. `reuse`: strands of an
  // earlier update the caller is done with; the new strands are written into their storage
  // (a fresh allocation's page faults cost as much as the growth, StrandGrower).
  LiveUpdate update(const std::vector<StylePrimitive>& primitives, Strands reuse = {});
  // The same, then `details` in order. Throws InvalidArgument for a detail out of its domain or
  // whose region names a vertex the head does not have; the strands are then unchanged.
  LiveUpdate update(const std::vector<StylePrimitive>& primitives, const std::vector<StrandDetail>& details,
                    Strands reuse = {});

  // The strands of every `stride`-th root only (roots 0, stride, 2·stride, …), `details`
  // applied: what a view that draws only that subset shows, at a fraction of the growth's cost.
  // Each is the strand update() gives for its root, point for point (clumps' guides are grown
  // too, detail_guides). Solves as update() does; a following update() with the same primitives
  // then only grows the rest. Throws InvalidArgument for a stride below 1, and as update() does.
  LiveUpdate preview(const std::vector<StylePrimitive>& primitives, const std::vector<StrandDetail>& details,
                     int stride);

  const HairstyleSettings& settings() const { return settings_; }
  const hair_field::Grid& grid() const { return field_.grid(); }
  // The field the strands grew in: the avoidance solve's where it ran, else the style's.
  const hair_field::Field& field() const { return avoided_used_ ? avoided_->field() : field_.field(); }
  const std::vector<Eigen::Vector3d>& roots() const { return roots_; }

 private:
  // Checks the details (naming fn), then brings the field up to date with `primitives` (both
  // solves, where they changed), recording the solves, constraints and time in `out`.
  void solve_if_changed(const std::vector<StylePrimitive>& primitives, const std::vector<StrandDetail>& details,
                        const char* fn, LiveUpdate& out);
  void solve(const std::vector<StylePrimitive>& primitives, LiveUpdate& out);
  // Makes the head's clearance and the detail context where growth or detail first needs them.
  void prepare_clearance(const std::vector<StrandDetail>& details);
  // The field's sampled copy for growth (with the clearance when growth keeps out of the head).
  SampledField sampled_field() const;

  const Head* head_;
  HairstyleSettings settings_;
  StyleField field_;  // the primitives' constraints only
  // The primitives' constraints and scalp avoidance's (§4.6), in a solver of its own: the
  // avoidance's near-head nodes are the same from edit to edit, so each solver only sees the
  // edit's diff. One solver would drop and re-add all of them twice per edit.
  std::unique_ptr<StyleField> avoided_;
  bool avoided_used_ = false;  // the last update's field is avoided_'s
  std::vector<Eigen::Vector3d> roots_;
  StrandGrower grower_;
  // The primitives the field was last solved for, and the strands as grown in that field
  // (before detail) when grown_valid_.
  std::vector<StylePrimitive> solved_primitives_;
  bool solved_valid_ = false;
  Strands grown_;
  bool grown_valid_ = false;
  StrandGrower preview_grower_;  // a buffer of its own, so a preview leaves grown_ alone
  // Made on the first update that grows strands out of the head or has details: the
  // clearance costs a hundred closest-point queries per refined cell, which the thesis' growth
  // without detail never needs.
  std::unique_ptr<HeadClearance> clearance_;
  std::unique_ptr<ScalpAvoidance> avoidance_;  // made on the first update that needs it
  DetailContext detail_context_;
};

}  // namespace lapis::hair_sketch
