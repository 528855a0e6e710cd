// The deform app's mouse and keys: the gizmo takes a press that hits it (in any tool), the
// brush and the lasso paint the current target (through the surface with x-ray on), a click
// of the connected or geodesic tool selects a region, keys switch tools and targets.
#include <GLFW/glfw3.h>

#include "deform_app.h"
#include "lapis/viewer/surface_select.h"

namespace lapis::deform_app {

bool DeformApp::on_event(viewer::Viewer& v, const viewer::InputEvent& e) {
  using viewer::EventType;
  if (leave_prompt_) {  // the unsaved-edits prompt is modal: its keys, nothing else
    if (e.type == EventType::Key && e.action == GLFW_PRESS && e.mods == 0) {
      if (e.key == GLFW_KEY_S) leave(v, LeaveChoice::Save);
      if (e.key == GLFW_KEY_D) leave(v, LeaveChoice::Discard);
      if (e.key == GLFW_KEY_ESCAPE) leave(v, LeaveChoice::Stay);
    }
    return true;
  }
  if (e.type == EventType::Key) return handle_key(v, e);
  if (e.type == EventType::MouseButton && e.button == GLFW_MOUSE_BUTTON_LEFT) {
    if (e.action == GLFW_PRESS) return press(v, {e.x, e.y}, e.mods);
    if (e.action == GLFW_RELEASE && (dragging_ || stroke_)) {
      release(v);
      return true;
    }
  }
  if (e.type == EventType::MouseMove) {
    if (dragging_ || stroke_) {
      move(v, {e.x, e.y});
      return true;
    }
    gizmo_.hovered = gizmo_shown() ? gizmo_.hit(v.camera_matrices(), {e.x, e.y}) : viewer::GizmoPart::None;
  }
  return false;
}

bool DeformApp::handle_key(viewer::Viewer& v, const viewer::InputEvent& e) {
  if (e.action != GLFW_PRESS && e.action != GLFW_REPEAT) return false;
  if (e.mods & GLFW_MOD_CONTROL) return handle_command_key(v, e.key, e.mods & GLFW_MOD_SHIFT);
  return handle_tool_key(e.key) || handle_edit_key(v, e.key);
}

// Ctrl+key: history, files, export.
bool DeformApp::handle_command_key(viewer::Viewer& v, int key, bool shift) {
  switch (key) {
    case GLFW_KEY_Z:
      shift ? redo(v) : undo(v);
      return true;
    case GLFW_KEY_Y:
      redo(v);
      return true;
    case GLFW_KEY_S:
      save_selection(v);
      return true;
    case GLFW_KEY_O:
      load_selection(v);
      return true;
    case GLFW_KEY_E:
      export_result(v);
      return true;
    case GLFW_KEY_M:
      mirror_target(v);
      return true;
    default:
      return false;  // Ctrl+P, Ctrl+Q: the viewer's
  }
}

// Keys that choose what the mouse does: tool, paint target, handle, brush size, colours.
bool DeformApp::handle_tool_key(int key) {
  switch (key) {
    case GLFW_KEY_M:
      tool_ = Tool::Move;
      return true;
    case GLFW_KEY_B:
      tool_ = Tool::Brush;
      return true;
    case GLFW_KEY_L:
      tool_ = Tool::Lasso;
      return true;
    case GLFW_KEY_K:
      tool_ = Tool::Connected;
      return true;
    case GLFW_KEY_G:
      tool_ = Tool::Geodesic;
      return true;
    case GLFW_KEY_X:
      xray_ = !xray_;
      surface_dirty_ = markers_dirty_ = true;
      return true;
    case GLFW_KEY_P:
      if (!pairing_) return false;
      tool_ = Tool::Pair;
      return true;
    case GLFW_KEY_1:
      target_ = VertexLabels::kRoi;
      return true;
    case GLFW_KEY_2:
      target_ = VertexLabels::kFixed;
      return true;
    case GLFW_KEY_3:
      target_ = 0;
      return true;
    case GLFW_KEY_4:
      target_ = VertexLabels::kNone;
      return true;
    case GLFW_KEY_TAB:
      select_next_painted_handle();
      return true;
    case GLFW_KEY_LEFT_BRACKET:  // the size of what the tool selects
      if (tool_ == Tool::Geodesic)
        geodesic_radius_ = std::max(0.002f, geodesic_radius_ / 1.25f);
      else
        brush_px_ = std::max(3.0f, brush_px_ / 1.25f);
      return true;
    case GLFW_KEY_RIGHT_BRACKET:
      if (tool_ == Tool::Geodesic)
        geodesic_radius_ = std::min(1.0f, geodesic_radius_ * 1.25f);
      else
        brush_px_ = std::min(300.0f, brush_px_ * 1.25f);
      return true;
    case GLFW_KEY_C:
      color_mode_ = color_mode_ == ColorMode::Selection ? ColorMode::Distortion : ColorMode::Selection;
      surface_dirty_ = true;
      return true;
    default:
      return false;
  }
}

// Keys that change the selection or the pose.
bool DeformApp::handle_edit_key(viewer::Viewer& v, int key) {
  switch (key) {
    case GLFW_KEY_N:
      new_handle();
      return true;
    case GLFW_KEY_EQUAL:
    case GLFW_KEY_KP_ADD:
      grow_or_shrink(v, 1);
      return true;
    case GLFW_KEY_MINUS:
    case GLFW_KEY_KP_SUBTRACT:
      grow_or_shrink(v, -1);
      return true;
    case GLFW_KEY_R:
      reset_pose(v);
      return true;
    case GLFW_KEY_DELETE:
      clear_target(v);
      return true;
    default:
      return false;
  }
}

void DeformApp::select_next_painted_handle() {
  const int n = state_.labels->handle_count();
  for (int k = 1; k <= n; ++k)
    if (state_.labels->any((state_.active_handle + k) % n)) {
      state_.active_handle = (state_.active_handle + k) % n;
      return;
    }
}

int DeformApp::paint_value() const { return erase_ ? VertexLabels::kNone : target_value(); }

int DeformApp::target_value() const { return target_ >= 0 ? state_.active_handle : target_; }

void DeformApp::ensure_pick_structures() {
  // Picking follows what is on screen: the BVH is rebuilt on the displayed positions the
  // first time a stroke needs it after they changed.
  if (pick_bvh_ && !pick_stale_) return;
  pick_bvh_ = std::make_unique<geometry::Bvh>(shown_);
  pick_stale_ = false;
}

bool DeformApp::press(viewer::Viewer& v, const Eigen::Vector2d& p, int mods) {
  const auto cam = v.camera_matrices();
  if (gizmo_shown() && gizmo_.begin_drag(cam, p)) {
    dragging_ = true;
    preview_gap_ = -1;
    drag_start_ = active_transform();
    return true;
  }
  if (tool_ == Tool::Move) return false;  // the camera's
  if (tool_ == Tool::Pair) return pair_at(v, p);
  if (tool_ == Tool::Connected || tool_ == Tool::Geodesic) return select_at(v, p, mods & GLFW_MOD_SHIFT);
  erase_ = mods & GLFW_MOD_SHIFT;
  stroke_ = std::make_shared<VertexLabels>(*state_.labels);
  if (target_ == kFeatureTarget) feature_stroke_ = features_.feature_of;
  if (tool_ == Tool::Brush) {
    last_paint_ = p;
    paint_at(v, p);
  } else {
    lasso_.assign(1, p);
    markers_dirty_ = true;
  }
  return true;
}

void DeformApp::move(viewer::Viewer& v, const Eigen::Vector2d& p) {
  if (dragging_) {
    active_transform() = gizmo_.drag_to(p) * drag_start_;
    ++drag_frames_;
    return;
  }
  if (tool_ == Tool::Brush) {
    // Dabs every half radius along the path, so a fast stroke leaves no gaps.
    const double step = std::max(1.0, 0.5 * brush_px_);
    const double length = (p - last_paint_).norm();
    for (double t = step; t < length; t += step) paint_at(v, last_paint_ + (p - last_paint_) * (t / length));
    paint_at(v, p);
    last_paint_ = p;
  } else if (tool_ == Tool::Lasso && (p - lasso_.back()).norm() >= 3) {
    lasso_.push_back(p);
    markers_dirty_ = true;
  }
}

void DeformApp::paint_at(viewer::Viewer& v, const Eigen::Vector2d& p) {
  ensure_pick_structures();
  const std::vector<int> vs =
      viewer::brush_vertices(shown_, *conn_, *pick_bvh_, v.camera_matrices(), p, {brush_px_, xray_});
  if (feature_stroke_)
    for (int i : vs) (*feature_stroke_)[static_cast<size_t>(i)] = erase_ ? FeatureLabels::kNone : active_feature_;
  else
    stroke_->paint(vs, paint_value());
  surface_dirty_ = true;
}

void DeformApp::release(viewer::Viewer& v) {
  if (dragging_) {
    gizmo_.end_drag();
    dragging_ = false;
    commit(std::string("move handle ") + std::to_string(state_.active_handle));
    return;  // the next request is the full pipeline (preview off)
  }
  std::vector<int> lassoed;
  if (tool_ == Tool::Lasso && lasso_.size() >= 3) {
    ensure_pick_structures();
    lassoed = viewer::lasso_vertices(shown_, *pick_bvh_, v.camera_matrices(), lasso_, {.visible_only = !xray_});
    if (!feature_stroke_) stroke_->paint(lassoed, paint_value());
  }
  lasso_.clear();
  markers_dirty_ = true;
  if (feature_stroke_) {  // a feature stroke: the labels stay, the features change
    stroke_.reset();
    std::vector<int> painted = std::move(*feature_stroke_);
    feature_stroke_.reset();
    for (int i : lassoed) painted[static_cast<size_t>(i)] = erase_ ? FeatureLabels::kNone : active_feature_;
    return commit_features(std::move(painted));
  }
  auto labels = std::move(stroke_);
  stroke_.reset();
  if (labels->label == state_.labels->label) return;  // painted nothing new
  const int value = paint_value();
  set_labels(std::move(labels), std::string(tool_name(tool_)) + (value == VertexLabels::kNone ? " erase" : " paint"));
}

void DeformApp::commit_features(std::vector<int> feature_of) {
  if (feature_of == features_.feature_of) return;
  features_.feature_of = std::move(feature_of);
  features_.count = std::max(features_.count, active_feature_ + 1);
  features_edited_ = true;
  ++features_revision_;
  surface_dirty_ = true;
}

void DeformApp::paint_set(viewer::Viewer& v, const std::vector<int>& vertices, const std::string& label) {
  if (vertices.empty()) return v.flash(label + ": nothing selected");
  if (target_ == kFeatureTarget) {
    std::vector<int> painted = features_.feature_of;
    painted.resize(static_cast<size_t>(rest_.num_vertices()), FeatureLabels::kNone);
    for (int i : vertices) painted[static_cast<size_t>(i)] = erase_ ? FeatureLabels::kNone : active_feature_;
    return commit_features(std::move(painted));
  }
  auto labels = std::make_shared<VertexLabels>(*state_.labels);
  labels->paint(vertices, paint_value());
  if (labels->label == state_.labels->label) return v.flash(label + ": nothing new");
  set_labels(std::move(labels), label + (erase_ ? " erase" : " paint"));
}

void DeformApp::grow_or_shrink(viewer::Viewer& v, int rings) {
  const int value = target_value();
  if (value == VertexLabels::kNone) return v.flash("grow/shrink: pick ROI, fixed or handle as the target");
  if (state_.labels->acting_as(value).empty()) return v.flash("grow/shrink: nothing acts as the current target yet");
  auto labels = std::make_shared<VertexLabels>(*state_.labels);
  grow_labels(*labels, *conn_, value, rings);
  if (labels->label == state_.labels->label)
    return v.flash(rings > 0 ? "grow: nothing to grow into" : "shrink: nothing left to shrink");
  set_labels(std::move(labels), rings > 0 ? "grow" : "shrink");
}

void DeformApp::clear_target(viewer::Viewer& v) {
  const int value = target_value();
  auto labels = std::make_shared<VertexLabels>(*state_.labels);
  if (value == VertexLabels::kNone) {
    labels = std::make_shared<VertexLabels>(rest_.num_vertices());  // erase target: clear everything
  } else {
    labels->paint(labels->with(value), VertexLabels::kNone);
  }
  if (labels->label == state_.labels->label) return v.flash("clear: nothing to clear");
  set_labels(std::move(labels), "clear");
}

}  // namespace lapis::deform_app
