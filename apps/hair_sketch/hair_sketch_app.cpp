#include "hair_sketch_app.h"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "lapis/core/atomic_file.h"
#include "lapis/hair_sketch/export.h"
#include "lapis/hair_sketch/hair_file.h"
#include "lapis/hair_sketch/session.h"
#include "lapis/hair_sketch/sketch.h"
#include "lapis/hair_sketch/stroke_commands.h"
#include "lapis/hair_sketch/style_field.h"
#include "lapis/hair_sketch/symmetry.h"
#include "primitive_geometry.h"
#include "strand_display.h"

namespace lapis::hair_app {
const char* tool_name(Tool t) {
  switch (t) {
    case Tool::StreamCurve:
      return "stream curve";
    case Tool::DividingCurve:
      return "dividing curve";
    case Tool::Ponytail:
      return "ponytail";
    case Tool::Hint:
      return "hint edit";
    case Tool::Tilt:
      return "tilt edit";
    case Tool::Select:
      return "select";
    case Tool::Cut:
      return "cut line";
    case Tool::Region:
      return "detail region";
  }
  return "?";
}

HairSketchApp::HairSketchApp(Head head, Hairstyle style, AppPaths paths)
    : head_(std::move(head)), document_(std::move(style)), paths_(std::move(paths)) {
  grid_ = hairstyle_grid(head_, document_.style().settings);
}

HairSketchApp::~HairSketchApp() = default;

void HairSketchApp::on_start(viewer::Viewer& v) {
  v.set_default_screenshot("out/hair_screenshot.png");  // Ctrl+P and the panel's button alike
  worker_.set_on_done([&v] { v.wake(); });              // new strands: redraw now, not at the next tick
  if (v.options().headless && !strand_budget_.pinned()) strand_budget_.pin(0);  // draw every strand
  update_head_item(v);
  const auto& cam = document_.style().camera;
  const bool has_camera = !cam.view.isIdentity() && cam.viewport[2] > 1;
  v.frame_scene();
  if (has_camera) {
    // A session's camera: place the orbit camera at its eye, looking at the head.
    const Eigen::Vector3d eye = geometry::eye_position(cam);
    const Eigen::Vector3d d = eye - v.camera().target;
    v.camera().distance = d.norm();
    v.camera().yaw = std::atan2(d.x(), d.z());
    v.camera().pitch = std::asin(std::clamp(d.y() / d.norm(), -1.0, 1.0));
  }
  last_autosave_ = v.time();
  request_regrowth();
}

bool HairSketchApp::busy() const {
  if (!engine_error_.empty()) return false;  // nothing more is coming
  return worker_.busy() || !last_ || last_->revision != document_.revision() ||
         last_->settings_epoch != settings_epoch_;
}

// ---------------------------------------------------------------- input

bool HairSketchApp::on_event(viewer::Viewer& v, const viewer::InputEvent& e) {
  using viewer::EventType;
  if (e.type == EventType::Key) return handle_key(v, e);
  if (e.type == EventType::MouseButton && e.button == GLFW_MOUSE_BUTTON_LEFT) {
    const Eigen::Vector2d p(e.x, e.y);
    if (e.action == GLFW_PRESS) {
      if (tool_ == Tool::Select)
        select_at(v, p);
      else
        begin_stroke(v, p);
      return true;
    }
    if (e.action == GLFW_RELEASE && drawing_) {
      finish_stroke(v);
      return true;
    }
  }
  if (e.type == EventType::MouseMove && drawing_) {
    extend_stroke(v, {e.x, e.y});
    return true;
  }
  return false;
}

bool HairSketchApp::handle_key(viewer::Viewer& v, const viewer::InputEvent& e) {
  if (e.action != GLFW_PRESS) return false;
  const bool ctrl = e.mods & GLFW_MOD_CONTROL, shift = e.mods & GLFW_MOD_SHIFT;
  if (ctrl && e.key == GLFW_KEY_Z) {
    shift ? redo(v) : undo(v);
    return true;
  }
  if (ctrl && e.key == GLFW_KEY_Y) return redo(v), true;
  if (ctrl && e.key == GLFW_KEY_S) return save(v, paths_.session), true;
  if (ctrl && e.key == GLFW_KEY_O) return load(v, paths_.session), true;
  if (ctrl && e.key == GLFW_KEY_E) return export_strands(v), true;
  if (ctrl) return false;
  if (e.key >= GLFW_KEY_1 && e.key <= GLFW_KEY_8) {
    tool_ = kTools[e.key - GLFW_KEY_1];
    ponytail_strokes_.clear();
    ponytail_cameras_.clear();
    curves_dirty_ = true;
    return true;
  }
  if (e.key == GLFW_KEY_DELETE || e.key == GLFW_KEY_BACKSPACE) return delete_selected(v), true;
  if (e.key == GLFW_KEY_M) {
    symmetric_ = !symmetric_;
    v.flash(symmetric_ ? "symmetric sketching on: new curves get a mirrored twin" : "symmetric sketching off");
    return true;
  }
  if (e.key == GLFW_KEY_ESCAPE) {
    drawing_ = false;
    stroke_.clear();
    ponytail_strokes_.clear();
    ponytail_cameras_.clear();
    preview_.clear();
    return true;
  }
  return false;
}

void HairSketchApp::begin_stroke(viewer::Viewer& v, const Eigen::Vector2d& p) {
  if ((tool_ == Tool::Hint || tool_ == Tool::Tilt) && selected_ < 0) {
    v.flash(std::string(tool_name(tool_)) + ": select a curve first (tool 6, or click it in the list)",
            viewer::Tone::Warning);
    return;
  }
  if (tool_ == Tool::Region && selected_detail_ < 0) {
    v.flash("detail region: select a detail in the Detail panel first", viewer::Tone::Warning);
    return;
  }
  drawing_ = true;
  painted_.clear();
  if (tool_ == Tool::Region) paint_region(v, p);
  stroke_.assign(1, p);
  preview_.clear();
}

void HairSketchApp::extend_stroke(viewer::Viewer& v, const Eigen::Vector2d& p) {
  if ((p - stroke_.back()).norm() < 2.0) return;  // a mouse at rest adds nothing
  stroke_.push_back(p);
  if (tool_ == Tool::Region) paint_region(v, p);
  // The preview follows the mouse: the stroke's 3D curve where it can already be
  // interpreted, the raw stroke otherwise.
  preview_.clear();
  if (tool_ == Tool::StreamCurve && stroke_.size() >= 2) {
    try {
      preview_ = stream_curve_from_stroke(stroke_, v.camera_matrices(), head_,
                                          sketch_options(grid_, document_.style().settings))
                     .points;
    } catch (const StrokeRejected&) {
    }
  }
  update_preview_item(v);
}

void HairSketchApp::finish_stroke(viewer::Viewer& v) {
  const double released = v.time();  // the edit's clock starts here: interpreting the stroke counts
  drawing_ = false;
  preview_.clear();
  RecordedStroke rec;
  rec.camera = v.camera_matrices();
  rec.mirrored = symmetric_;
  switch (tool_) {
    case Tool::StreamCurve:
      rec.action = StrokeAction::StreamCurve;
      break;
    case Tool::DividingCurve:
      rec.action = StrokeAction::DividingCurve;
      break;
    case Tool::Ponytail:
      rec.action = StrokeAction::Ponytail;
      break;
    case Tool::Hint:
      rec.action = StrokeAction::Hint, rec.target = selected_;
      break;
    case Tool::Tilt:
      rec.action = StrokeAction::Tilt, rec.target = selected_;
      break;
    case Tool::Select:
      return;
    case Tool::Cut:
      return add_cut_line(v);
    case Tool::Region: {
      std::vector<StrandDetail> details = document_.style().details;
      if (selected_detail_ < 0 || selected_detail_ >= static_cast<int>(details.size())) return;
      std::set<int> region(details[selected_detail_].region.begin(), details[selected_detail_].region.end());
      region.insert(painted_.begin(), painted_.end());
      details[selected_detail_].region.assign(region.begin(), region.end());
      painted_.clear();
      stroke_.clear();
      update_preview_item(v);
      return set_details(v, std::move(details), "paint detail region");
    }
  }
  if (tool_ == Tool::Ponytail) {
    ponytail_strokes_.push_back(stroke_);
    ponytail_cameras_.push_back(rec.camera);  // the view may turn between the strokes (§4.5)
    stroke_.clear();
    if (ponytail_strokes_.size() < 4) {
      curves_dirty_ = true;
      update_preview_item(v);
      return;
    }
    rec.strokes = std::move(ponytail_strokes_);
    ponytail_strokes_.clear();
    const auto& first = ponytail_cameras_.front();
    const bool one_view = std::all_of(ponytail_cameras_.begin(), ponytail_cameras_.end(), [&](const auto& c) {
      return c.view == first.view && c.projection == first.projection && c.viewport == first.viewport;
    });
    if (!one_view) rec.cameras = std::move(ponytail_cameras_);
    ponytail_cameras_.clear();
  } else {
    rec.strokes = {std::move(stroke_)};
    stroke_.clear();
  }
  try {
    const size_t before = document_.style().primitives.size();
    apply_stroke(document_, rec, head_, grid_);
    if (document_.style().primitives.size() > before) selected_ = static_cast<int>(before);
    if (rec.action == StrokeAction::Ponytail) warn_if_tail_too_thin(v, document_.style().primitives.back());
    begin_edit(released);
    return;  // the stroke stays on screen until its strands arrive (on_frame)
  } catch (const StrokeRejected& e) {
    // "hair_sketch::stream_curve_from_stroke(): stroke must start on the scalp" → the reason.
    std::string why = e.what();
    const auto colon = why.find("(): ");
    v.flash("stroke rejected: " + (colon == std::string::npos ? why : why.substr(colon + 4)), viewer::Tone::Warning);
  }
  update_preview_item(v);
}

// A cross-section narrower than a grid cell has no grid node inside C1. Without the gravity
// prior, the thesis' field then gathers few strands into it, and the tail would stay nearly
// empty. Say so, and what to change.
void HairSketchApp::warn_if_tail_too_thin(viewer::Viewer& v, const StylePrimitive& p) {
  const auto* tail = std::get_if<Ponytail>(&p.shape);
  if (!tail) return;
  const double r = tail->first_section().radius;
  // With the gravity prior, the hair above the tail falls into it however thin it is.
  if (r >= grid_.spacing || document_.style().settings.gravity_prior.strength > 0) return;
  char text[240];
  std::snprintf(text, sizeof text,
                "ponytail cross-section radius %.3f is below the grid spacing %.3f: with the gravity prior off, "
                "few strands will reach it; turn the prior on, draw it wider or raise the grid unknowns",
                r, grid_.spacing);
  v.flash(text, viewer::Tone::Warning);
}

void HairSketchApp::select_at(viewer::Viewer& v, const Eigen::Vector2d& p) {
  const auto cam = v.camera_matrices();
  double best = 12.0;  // pixels
  int found = -1;
  const auto& prims = document_.style().primitives;
  for (size_t i = 0; i < prims.size(); ++i) {
    if (hidden_.count(static_cast<int>(i))) continue;
    auto lines = primitive_polylines(prims[i]);
    if (prims[i].mirrored)  // clicking the twin selects the primitive it follows
      for (auto& line : primitive_polylines(mirror_image(prims[i], head_.center.x()))) lines.push_back(std::move(line));
    for (const auto& line : lines)
      for (const auto& q : line) {
        const Eigen::Vector3d s = geometry::project(cam, q);
        const double d = (s.head<2>() - p).norm();
        if (s.z() > 0 && s.z() < 1 && d < best) best = d, found = static_cast<int>(i);
      }
  }
  selected_ = found;
  curves_dirty_ = true;
}

void HairSketchApp::execute(viewer::Viewer& v, Command command) {
  try {
    document_.execute(std::move(command));
  } catch (const Error& e) {
    v.flash(e.what(), viewer::Tone::Error);
    return;
  }
  begin_edit(v.time());
}

void HairSketchApp::begin_edit(double time) {
  last_edit_time_ = time;
  curves_dirty_ = true;
  scene_held_since_ = time;
  request_regrowth();
}

void HairSketchApp::end_scene_hold(viewer::Viewer& v) {
  scene_held_since_ = -1;
  update_preview_item(v);
}

void HairSketchApp::undo(viewer::Viewer& v) {
  if (!document_.can_undo()) return v.flash("nothing to undo");
  document_.undo();
  selected_ = std::min(selected_, static_cast<int>(document_.style().primitives.size()) - 1);
  head_dirty_ = true;  // the selected detail's region may have changed
  begin_edit(v.time());
}

void HairSketchApp::redo(viewer::Viewer& v) {
  if (!document_.can_redo()) return v.flash("nothing to redo");
  document_.redo();
  head_dirty_ = true;
  begin_edit(v.time());
}

void HairSketchApp::delete_selected(viewer::Viewer& v) {
  if (selected_ < 0) return;
  execute(v, Command{"delete primitive", RemovePrimitive{selected_}, std::nullopt});
  hidden_.erase(selected_);
  selected_ = -1;
}

// ---------------------------------------------------------------- files

void HairSketchApp::save(viewer::Viewer& v, const std::filesystem::path& path) {
  try {
    Hairstyle style = document_.style();
    style.camera = v.camera_matrices();
    core::create_parent_directories(path);
    save_session(path, style);
    v.flash("saved " + path.string(), viewer::Tone::Success);
    std::printf("saved session: %s\n", path.string().c_str());
  } catch (const Error& e) {
    v.flash(std::string("save failed: ") + e.what(), viewer::Tone::Error);
  }
}

void HairSketchApp::load(viewer::Viewer& v, const std::filesystem::path& path) {
  try {
    Hairstyle style = load_session(path);
    Head head = load_session_head(style, path);
    worker_.wait();  // jobs read head_ and the engine: replace them only when idle
    (void)worker_.take();
    head_ = std::move(head);
    document_ = Document(std::move(style));
    selected_ = -1;
    hidden_.clear();
    head_dirty_ = curves_dirty_ = true;
    settings_changed();
    v.flash("opened " + path.string(), viewer::Tone::Success);
  } catch (const Error& e) {
    v.flash(std::string("open failed: ") + e.what(), viewer::Tone::Error);
  }
}

bool HairSketchApp::export_strands(viewer::Viewer& v) {
  if (!last_) {
    v.flash("no strands yet");
    return false;
  }
  try {
    for (const auto* p : {&paths_.export_hair, &paths_.export_obj}) core::create_parent_directories(*p);
    core::AtomicFileGroup pair;  // both new or both old, never a new .hair beside an old .obj
    const Strands grown = grown_strands(last_->update.strands);  // not the roots that grew nothing
    write_hair_file(paths_.export_hair, to_hair_file(grown));
    write_strands_obj(paths_.export_obj, grown);
    pair.commit();
    v.flash("exported " + paths_.export_hair.string() + " and " + paths_.export_obj.string(), viewer::Tone::Success);
    return true;
  } catch (const Error& e) {
    v.flash(std::string("export failed: ") + e.what(), viewer::Tone::Error);
    std::fprintf(stderr, "lapis-hair-sketch: export failed: %s\n", e.what());
    return false;
  }
}

void HairSketchApp::autosave_if_due(viewer::Viewer& v) {
  if (v.time() - last_autosave_ < 60.0) return;
  last_autosave_ = v.time();
  try {
    save_session(paths_.autosave, document_.style());
  } catch (const Error& e) {
    v.flash(std::string("autosave failed: ") + e.what(), viewer::Tone::Error);
  }
}

void HairSketchApp::on_exit(viewer::Viewer& v) {
  if (preview_gate_) preview_gate_->open();
  worker_.wait();
  worker_.set_on_done({});  // the window goes away after this
  receive_regrowth(v);
  if (paths_.export_on_exit) {
    if (export_strands(v))
      std::printf("exported %s and %s\n", paths_.export_hair.string().c_str(), paths_.export_obj.string().c_str());
    else
      exit_status_ = 1;
  }
  try {
    Hairstyle style = document_.style();
    style.camera = v.camera_matrices();
    core::create_parent_directories(paths_.autosave);
    save_session(paths_.autosave, style);
  } catch (const Error& e) {
    std::fprintf(stderr, "lapis-hair-sketch: autosave on exit failed: %s\n", e.what());
  }
}

}  // namespace lapis::hair_app
