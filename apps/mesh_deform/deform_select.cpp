// The deform app's selection tools beyond the brush and the lasso: a click that takes the
// clicked vertex's connected region (or the part of it with the clicked label) or the vertices
// within a geodesic radius of it, the mirror image of what acts as the current target, and the
// warning when the ROI's border passes close to a handle.
#include <imgui.h>

#include <cstdio>

#include "deform_app.h"
#include "lapis/geometry/connected_region.h"
#include "lapis/geometry/geodesic_disc.h"
#include "lapis/geometry/mirror_vertices.h"
#include "lapis/geometry/region_border.h"
#include "lapis/viewer/picking.h"

namespace lapis::deform_app {
namespace {

const char* const kAxisNames[] = {"x", "y", "z"};
const ImVec4 kWarningColor(1.0f, 0.35f, 0.2f, 1.0f);

}  // namespace

double DeformApp::diagonal() const { return (rest_.V.colwise().maxCoeff() - rest_.V.colwise().minCoeff()).norm(); }

bool DeformApp::select_at(viewer::Viewer& v, const Eigen::Vector2d& p, bool erase) {
  ensure_pick_structures();
  const auto hit = viewer::pick(*pick_bvh_, v.camera_matrices(), p.x(), p.y());
  if (!hit) return false;  // beside the mesh: the camera's
  const int seed = viewer::nearest_corner(shown_, *hit);
  erase_ = erase;
  if (tool_ == Tool::Connected) {
    std::vector<char> allowed;
    if (connected_within_label_) {  // a bucket fill: only across vertices labelled like the clicked one
      const std::vector<int>& label = state_.labels->label;
      allowed.resize(label.size());
      for (size_t i = 0; i < label.size(); ++i) allowed[i] = label[i] == label[static_cast<size_t>(seed)];
    }
    paint_set(v, geometry::connected_region(*conn_, seed, allowed), "connected");
  } else {
    // On the rest mesh: the labels are the rest mesh's, whatever pose is on screen.
    paint_set(v, geometry::geodesic_disc(rest_, *conn_, seed, geodesic_radius_ * diagonal()), "geodesic");
  }
  return true;
}

int DeformApp::mirror_axis() {
  if (mirror_choice_ > 0) return mirror_choice_ - 1;
  if (auto_mirror_axis_ >= 0) return auto_mirror_axis_;
  // Auto: the plane about which most of a sample of the vertices find their image.
  const Eigen::Vector3d lo = rest_.V.colwise().minCoeff(), hi = rest_.V.colwise().maxCoeff();
  std::vector<int> sample;
  const int n = rest_.num_vertices(), step = std::max(1, n / 2000);
  for (int i = 0; i < n; i += step) sample.push_back(i);
  size_t best = 0;
  for (int axis = 0; axis < 3; ++axis) {
    const auto m = geometry::mirror_vertices(rest_.V, sample, 0.5 * (lo + hi), Eigen::Vector3d::Unit(axis),
                                             mirror_tolerance_ * diagonal());
    if (axis == 0 || m.unmatched.size() < best) best = m.unmatched.size(), auto_mirror_axis_ = axis;
  }
  return auto_mirror_axis_;
}

void DeformApp::mirror_target(viewer::Viewer& v) {
  const int value = target_value();
  std::vector<int> set;
  if (target_ == kFeatureTarget) {
    for (size_t i = 0; i < features_.feature_of.size(); ++i)
      if (features_.feature_of[i] == active_feature_) set.push_back(static_cast<int>(i));
  } else if (value == VertexLabels::kNone) {
    return v.flash("mirror: pick ROI, fixed or handle as the target");
  } else {
    set = state_.labels->acting_as(value);
  }
  if (set.empty()) return v.flash("mirror: nothing acts as the current target yet");
  const int axis = mirror_axis();
  const Eigen::Vector3d centre = 0.5 * (rest_.V.colwise().minCoeff() + rest_.V.colwise().maxCoeff()).transpose();
  const geometry::MirroredVertices m =
      geometry::mirror_vertices(rest_.V, set, centre, Eigen::Vector3d::Unit(axis), mirror_tolerance_ * diagonal());
  char status[200];
  std::snprintf(status, sizeof status,
                "mirror across %s%s: %zu of %zu vertices matched, %zu without a vertex within %.2g%%", kAxisNames[axis],
                mirror_choice_ == 0 ? " (auto)" : "", set.size() - m.unmatched.size(), set.size(), m.unmatched.size(),
                100.0 * mirror_tolerance_);
  v.flash(status);
  erase_ = false;
  if (target_ == kFeatureTarget) return paint_set(v, m.vertices, "mirror");
  // Painted so that the images act as the target, whichever label that takes (an image in the
  // fixed region joins the ROI when the target is the ROI).
  auto labels = std::make_shared<VertexLabels>(*state_.labels);
  labels->make_act_as(m.vertices, value);
  if (labels->label == state_.labels->label) return;  // already symmetric: the status says how it matched
  set_labels(std::move(labels), std::string("mirror across ") + kAxisNames[axis]);
}

void DeformApp::update_roi_warning() {
  std::vector<int> warned;
  std::string text;
  if (selection_) {
    const Selection& s = selection_->selection;
    std::vector<char> in_roi(static_cast<size_t>(rest_.num_vertices()), 0);
    for (int i : s.roi) in_roi[static_cast<size_t>(i)] = 1;
    for (size_t k = 0; k < s.region_handles.size(); ++k) {
      const std::vector<int> near = geometry::near_region_border(*conn_, in_roi, s.region_handles[k], kWarnRings);
      if (near.empty()) continue;
      char line[200];
      std::snprintf(line, sizeof line, "%shandle %d: %zu of %zu vertices within %d rings of the fixed region",
                    text.empty() ? "" : "; ", selection_->handle_label[k], near.size(), s.region_handles[k].size(),
                    kWarnRings);
      text += line;
      warned.insert(warned.end(), near.begin(), near.end());
    }
  }
  if (text != roi_warning_) {  // logged once per change, for batch runs and tests
    if (!text.empty())
      std::fprintf(stderr, "lapis-deform: warning: the ROI's border cuts close to a handle: %s\n", text.c_str());
    else if (!roi_warning_.empty())
      std::fprintf(stderr, "lapis-deform: the ROI's border is clear of the handles\n");
  }
  roi_warning_ = std::move(text);
  warned_vertices_ = std::move(warned);
  markers_dirty_ = true;
}

void DeformApp::draw_roi_warning(viewer::Viewer& v) {
  if (roi_warning_.empty()) return;
  // A short banner over the 3D view, between the overlay and the panels; the details in the
  // Selection panel.
  ImGui::SetNextWindowPos(ImVec2((static_cast<float>(v.width()) - 340) * 0.5f, 132), ImGuiCond_Always, ImVec2(0.5f, 0));
  ImGui::SetNextWindowBgAlpha(0.9f);
  ImGui::Begin("##roi warning", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoInputs |
                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav);
  ImGui::TextColored(kWarningColor, "ROI border cuts close to a handle (red points)");
  ImGui::End();
}

void DeformApp::draw_roi_warning_details() const {
  if (roi_warning_.empty()) return;
  ImGui::PushStyleColor(ImGuiCol_Text, kWarningColor);
  ImGui::TextWrapped("%s", roi_warning_.c_str());
  ImGui::PopStyleColor();
  ImGui::TextDisabled(
      "the fixed region there holds the handle back: paint the ROI around it (X: x-ray paints the back)");
}

}  // namespace lapis::deform_app
