// Painted selections: one label per vertex (unpainted, ROI, fixed, or region handle k), the
// way an interactive tool edits them, and the deformer Selection they stand for. Rules that
// keep every painting valid by construction: a vertex has one label, handles lie in the ROI,
// and an ROI that was never painted means "everything that is not fixed".
#pragma once

#include <vector>

#include "lapis/geometry/connectivity.h"
#include "lapis/mesh_deform/deformer.h"

namespace lapis::mesh_deform {

struct VertexLabels {
  static constexpr int kNone = -1, kRoi = -2, kFixed = -3;  // >= 0: region handle index
  std::vector<int> label;                                   // #V

  VertexLabels() = default;
  explicit VertexLabels(int num_vertices) : label(static_cast<size_t>(num_vertices), kNone) {}

  // Sets `vertices` to `value` (kNone erases). Throws InvalidArgument for an index out of
  // range or a value below kFixed.
  void paint(const std::vector<int>& vertices, int value);
  // Vertices carrying `value`, ascending.
  std::vector<int> with(int value) const;
  // One past the highest handle label in use (0: no handle).
  int handle_count() const;
  bool any(int value) const;

  // Vertices that act as `value` for the deformer, ascending: kRoi the ROI's vertices that are
  // not handles, kFixed the vertices outside the ROI (painted fixed, or unpainted once an ROI
  // is painted), k >= 0 handle k.
  std::vector<int> acting_as(int value) const;
  // Paints `vertices` so that they act as `value` (kRoi / kFixed / handle k), whichever label
  // that takes under the rules above.
  void make_act_as(const std::vector<int>& vertices, int value);
};

// Grows (rings > 0) or shrinks (rings < 0) the vertices acting as `value` by whole rings of
// `conn`. Growth does not take other handles' vertices; vertices a shrink gives up join the
// ROI (from a handle or the fixed region) or the fixed region (from the ROI).
void grow_labels(VertexLabels& labels, const geometry::Connectivity& conn, int value, int rings);

// The selection the labels stand for, and which label each of its region handles came from.
struct LabelledSelection {
  Selection selection;
  std::vector<int> handle_label;  // selection.region_handles[k] holds the vertices labelled handle_label[k]
};

// ROI = painted ROI plus the handles; when no ROI is painted, every vertex not painted fixed.
// Empty handle labels are skipped. Throws InvalidArgument "mesh_deform::to_selection(): ..."
// when no handle is painted or the ROI is empty (the deformer checks the rest).
LabelledSelection to_selection(const VertexLabels& labels);

// Labels for a selection read from files: ROI vertices kRoi, region handle k label k, point
// handle k label (number of region handles + k); everything else kNone (fixed, since the
// ROI is painted). Throws InvalidArgument for indices out of range.
VertexLabels from_selection(const Selection& selection, int num_vertices);

}  // namespace lapis::mesh_deform
