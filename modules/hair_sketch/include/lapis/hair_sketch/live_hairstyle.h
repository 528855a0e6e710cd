// The interactive loop of thesis ch. 4 as one object: a head, a grid and a field solver set
// up once; then, per document revision, the primitives' constraints are diffed against the
// previous ones and only the diff reaches the solver (§4.4.2), scalp avoidance is re-derived
// from the new field (§4.6), and the strands regrow from fixed roots (§4.6). The sketching
// app runs update() on a worker thread; build_hairstyle() is the one-shot equivalent.
#pragma once

#include <memory>
#include <vector>

#include "lapis/hair_sketch/document.h"
#include "lapis/hair_sketch/growth.h"
#include "lapis/hair_sketch/head.h"
#include "lapis/hair_sketch/style_field.h"

namespace lapis::hair_sketch {

struct LiveUpdate {
  Strands strands;
  std::vector<hair_field::FieldSolveReport> solves;  // the style solve, then the avoidance solve
  int constraints = 0;
  double solve_ms = 0;   // constraint diff + field update(s)
  double growth_ms = 0;  // regrowing every strand
  double total_ms = 0;
};

class LiveHairstyle {
 public:
  // Builds the grid, the solver and the roots for `settings`. The head must outlive this.
  // Throws ResourceLimit when the grid's solver would not fit in memory.
  LiveHairstyle(const Head& head, const HairstyleSettings& settings);

  // Brings the field and the strands up to date with `primitives`. `reuse`: strands of an
  // earlier update the caller is done with; the new strands are written into their storage
  // (a fresh allocation's page faults cost as much as the growth, StrandGrower).
  LiveUpdate update(const std::vector<StylePrimitive>& primitives, Strands reuse = {});

  const HairstyleSettings& settings() const { return settings_; }
  const hair_field::Grid& grid() const { return field_.grid(); }
  const hair_field::Field& field() const { return field_.field(); }
  const std::vector<Eigen::Vector3d>& roots() const { return roots_; }

 private:
  const Head* head_;
  HairstyleSettings settings_;
  StyleField field_;
  std::vector<Eigen::Vector3d> roots_;
  StrandGrower grower_;
};

}  // namespace lapis::hair_sketch
