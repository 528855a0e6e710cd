#include "lapis/mesh_deform/vertex_labels.h"

#include <algorithm>
#include <string>

namespace lapis::mesh_deform {
namespace {

void check(int v, int n, const char* fn) {
  if (v < 0 || v >= n)
    throw InvalidArgument(std::string(fn) + ": vertex " + std::to_string(v) + " out of range [0, " + std::to_string(n) +
                          ")");
}

}  // namespace

void VertexLabels::paint(const std::vector<int>& vertices, int value) {
  constexpr const char* fn = "mesh_deform::VertexLabels::paint()";
  if (value < kFixed) throw InvalidArgument(std::string(fn) + ": label " + std::to_string(value) + " is not a label");
  const int n = static_cast<int>(label.size());
  for (int v : vertices) check(v, n, fn);
  for (int v : vertices) label[static_cast<size_t>(v)] = value;
}

std::vector<int> VertexLabels::with(int value) const {
  std::vector<int> out;
  for (size_t v = 0; v < label.size(); ++v)
    if (label[v] == value) out.push_back(static_cast<int>(v));
  return out;
}

int VertexLabels::handle_count() const {
  int n = 0;
  for (int l : label) n = std::max(n, l + 1);
  return n;
}

bool VertexLabels::any(int value) const { return std::find(label.begin(), label.end(), value) != label.end(); }

std::vector<int> VertexLabels::acting_as(int value) const {
  if (value >= 0 || (value != kRoi && value != kFixed)) return with(value);
  const bool roi_painted = any(kRoi);
  std::vector<int> out;
  for (size_t v = 0; v < label.size(); ++v) {
    const int l = label[v];
    const bool fixed = l == kFixed || (l == kNone && roi_painted);
    if (l >= 0) continue;
    if ((value == kFixed) == fixed) out.push_back(static_cast<int>(v));
  }
  return out;
}

void VertexLabels::make_act_as(const std::vector<int>& vertices, int value) {
  // kNone means ROI while no ROI is painted and fixed once one is: pick the label that says
  // what is wanted whatever else gets painted later.
  if (value == kRoi && !any(kRoi)) {
    // Keep "unpainted = ROI" for the rest: painting kNone is enough.
    paint(vertices, kNone);
    return;
  }
  paint(vertices, value);
}

void grow_labels(VertexLabels& labels, const geometry::Connectivity& conn, int value, int rings) {
  constexpr const char* fn = "mesh_deform::grow_labels()";
  if (conn.num_vertices() != static_cast<int>(labels.label.size()))
    throw InvalidArgument(std::string(fn) + ": connectivity has " + std::to_string(conn.num_vertices()) +
                          " vertices, labels " + std::to_string(labels.label.size()));
  if (rings == 0) return;
  const std::vector<int> set = labels.acting_as(value);
  std::vector<char> in(labels.label.size(), 0);
  for (int v : set) in[static_cast<size_t>(v)] = 1;
  if (rings > 0) {
    if (set.empty()) return;
    std::vector<int> grown;
    for (int v : geometry::k_ring(conn, set, rings))
      if (!in[static_cast<size_t>(v)] &&
          (labels.label[static_cast<size_t>(v)] < 0 || labels.label[static_cast<size_t>(v)] == value))
        grown.push_back(v);
    labels.make_act_as(grown, value);
    return;
  }
  // Shrink: what lies within |rings| of the outside leaves.
  std::vector<int> outside;
  for (size_t v = 0; v < in.size(); ++v)
    if (!in[v]) outside.push_back(static_cast<int>(v));
  if (outside.empty()) return;
  std::vector<int> leaving;
  for (int v : geometry::k_ring(conn, outside, -rings))
    if (in[static_cast<size_t>(v)]) leaving.push_back(v);
  labels.make_act_as(leaving, value == VertexLabels::kRoi ? VertexLabels::kFixed : VertexLabels::kRoi);
}

LabelledSelection to_selection(const VertexLabels& labels) {
  constexpr const char* fn = "mesh_deform::to_selection()";
  LabelledSelection out;
  const int handles = labels.handle_count();
  std::vector<std::vector<int>> by_handle(static_cast<size_t>(handles));
  const bool roi_painted = labels.any(VertexLabels::kRoi);
  for (size_t v = 0; v < labels.label.size(); ++v) {
    const int l = labels.label[v];
    if (l >= 0) by_handle[static_cast<size_t>(l)].push_back(static_cast<int>(v));
    const bool in_roi = l >= 0 || l == VertexLabels::kRoi || (!roi_painted && l == VertexLabels::kNone);
    if (in_roi) out.selection.roi.push_back(static_cast<int>(v));
  }
  for (int h = 0; h < handles; ++h)
    if (!by_handle[static_cast<size_t>(h)].empty()) {
      out.selection.region_handles.push_back(std::move(by_handle[static_cast<size_t>(h)]));
      out.handle_label.push_back(h);
    }
  if (out.selection.region_handles.empty()) throw InvalidArgument(std::string(fn) + ": no handle painted");
  if (out.selection.roi.empty()) throw InvalidArgument(std::string(fn) + ": the ROI is empty");
  return out;
}

VertexLabels from_selection(const Selection& selection, int num_vertices) {
  constexpr const char* fn = "mesh_deform::from_selection()";
  VertexLabels labels(num_vertices);
  for (int v : selection.roi) check(v, num_vertices, fn), labels.label[static_cast<size_t>(v)] = VertexLabels::kRoi;
  int h = 0;
  for (const auto& handle : selection.region_handles) {
    for (int v : handle) check(v, num_vertices, fn), labels.label[static_cast<size_t>(v)] = h;
    ++h;
  }
  for (int v : selection.point_handles) check(v, num_vertices, fn), labels.label[static_cast<size_t>(v)] = h++;
  return labels;
}

}  // namespace lapis::mesh_deform
