// The hair app's Dear ImGui panels: tools, primitives and their parameters, settings, files,
// and the latency overlay. Every edit goes through a document command (undoable).
#include <imgui.h>

#include <cmath>
#include <numbers>

#include "hair_sketch_app.h"
#include "lapis/geometry/camera.h"
#include "lapis/viewer/panel_column.h"
#include "primitive_geometry.h"

namespace lapis::hair_app {
namespace {

// Applies `edit` to a copy of primitive i and executes it as one command when the widget
// that changed it is released (one undo step per drag, not per frame).
template <class Edit>
bool edit_on_release(StylePrimitive& copy, Edit&& widget) {
  widget(copy);
  return ImGui::IsItemDeactivatedAfterEdit();
}

const char* kToolKeys = "1 stream  2 dividing  3 ponytail  4 hint  5 tilt  6 select  7 cut line  8 detail region";

}  // namespace

void HairSketchApp::on_gui(viewer::Viewer& v) {
  // Tools, Primitives and Files down the right edge, each sized to its content.
  viewer::PanelColumn column(static_cast<float>(v.width()), static_cast<float>(v.height()), 320, 3);
  draw_toolbar(v, column);
  draw_primitive_panel(v, column);
  draw_detail_panel(v, column);
  draw_file_panel(v, column);
  draw_settings_panel(v);
  draw_overlay(v);
}

void HairSketchApp::draw_toolbar(viewer::Viewer& v, viewer::PanelColumn& column) {
  column.begin("Tools");
  for (int i = 0; i < static_cast<int>(std::size(kTools)); ++i) {
    if (i % 2) ImGui::SameLine(160);  // two a row: three cut "ponytail" at this width
    if (ImGui::RadioButton(tool_name(kTools[i]), tool_ == kTools[i])) {
      tool_ = kTools[i];
      ponytail_strokes_.clear();
      ponytail_cameras_.clear();
      curves_dirty_ = true;
    }
  }
  ImGui::Checkbox("symmetric (M)", &symmetric_);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("new curves get a twin mirrored across the head's sagittal plane");
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
  ImGui::TextWrapped("%s", kToolKeys);
  ImGui::PopStyleColor();
  ImGui::BeginDisabled(!document_.can_undo());
  if (ImGui::Button("Undo")) undo(v);
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::BeginDisabled(!document_.can_redo());
  if (ImGui::Button("Redo")) redo(v);
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::BeginDisabled(selected_ < 0);
  if (ImGui::Button("Delete")) delete_selected(v);
  ImGui::EndDisabled();
  column.end();
}

void HairSketchApp::draw_primitive_panel(viewer::Viewer& v, viewer::PanelColumn& column) {
  column.begin("Primitives");
  const auto& prims = document_.style().primitives;
  if (prims.empty()) ImGui::TextDisabled("none yet: draw a curve (tools 1-3)");
  for (size_t i = 0; i < prims.size(); ++i) {
    ImGui::PushID(static_cast<int>(i));
    bool visible = !hidden_.count(static_cast<int>(i));
    if (ImGui::Checkbox("##visible", &visible)) {
      if (visible)
        hidden_.erase(static_cast<int>(i));
      else
        hidden_.insert(static_cast<int>(i));
      curves_dirty_ = true;
    }
    ImGui::SameLine();
    const std::string label = std::to_string(i) + " " + primitive_type(prims[i]);
    if (ImGui::Selectable(label.c_str(), selected_ == static_cast<int>(i))) {
      selected_ = static_cast<int>(i);
      curves_dirty_ = true;
    }
    ImGui::PopID();
  }
  if (selected_ >= 0 && selected_ < static_cast<int>(prims.size())) {
    ImGui::Separator();
    StylePrimitive copy = prims[static_cast<size_t>(selected_)];
    bool commit = false;
    if (auto* s = std::get_if<StreamCurve>(&copy.shape)) {
      commit |=
          edit_on_release(copy, [&](StylePrimitive&) { ImGui::SliderInt("tail segments", &s->tail_segments, 0, 10); });
    } else if (auto* d = std::get_if<DividingCurve>(&copy.shape)) {
      float a0 = static_cast<float>(d->alpha0 * 180 / std::numbers::pi),
            a1 = static_cast<float>(d->alpha1 * 180 / std::numbers::pi);
      commit |= edit_on_release(copy, [&](StylePrimitive&) { ImGui::SliderFloat("tilt a0 (deg)", &a0, -90, 90); });
      commit |= edit_on_release(copy, [&](StylePrimitive&) { ImGui::SliderFloat("tilt a1 (deg)", &a1, -90, 90); });
      d->alpha0 = a0 * std::numbers::pi / 180, d->alpha1 = a1 * std::numbers::pi / 180;
      float sigma = static_cast<float>(d->sigma), h = static_cast<float>(d->height),
            disc = static_cast<float>(d->discontinuity);
      commit |= edit_on_release(copy, [&](StylePrimitive&) { ImGui::SliderFloat("sigma", &sigma, 0.25f, 4.0f); });
      commit |= edit_on_release(copy, [&](StylePrimitive&) { ImGui::SliderFloat("h", &h, 0.1f, 2.0f); });
      commit |= edit_on_release(copy, [&](StylePrimitive&) { ImGui::SliderFloat("discontinuity", &disc, 0.0f, 1.0f); });
      d->sigma = sigma, d->height = h, d->discontinuity = disc;
    } else if (auto* p = std::get_if<Ponytail>(&copy.shape)) {
      float t = static_cast<float>(p->tightness);
      commit |= edit_on_release(copy, [&](StylePrimitive&) { ImGui::SliderFloat("tightness", &t, 0.0f, 1.0f); });
      p->tightness = t;
    }
    if (ImGui::Checkbox("mirrored twin", &copy.mirrored)) commit = true;
    int mode = copy.support == SupportMode::Ruled ? 0 : 1;
    if (ImGui::Combo("supporting surface", &mode, "ruled\0strip\0")) {
      copy.support = mode == 0 ? SupportMode::Ruled : SupportMode::Strip;
      commit = true;
    }
    if (ImGui::Button("viewpoint := current camera")) {
      copy.viewpoint = geometry::eye_position(v.camera_matrices());
      commit = true;
    }
    if (commit)
      execute(v, Command{"edit " + std::string(primitive_type(copy)), ReplacePrimitive{selected_, copy}, std::nullopt});
  }
  column.end();
}

void HairSketchApp::draw_settings_panel(viewer::Viewer& v) {
  ImGui::SetNextWindowPos(ImVec2(10, static_cast<float>(v.height()) - 336), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(350, 326), ImGuiCond_FirstUseEver);  // scrolls: the view stays clear
  ImGui::Begin("Hair");
  HairstyleSettings s = document_.style().settings;
  bool changed = false;
  int unknowns = static_cast<int>(s.grid.target_unknowns);
  ImGui::SliderInt("grid unknowns", &unknowns, 5000, 1000000, "%d", ImGuiSliderFlags_Logarithmic);
  if (ImGui::IsItemDeactivatedAfterEdit()) s.grid.target_unknowns = unknowns, changed = true;
  ImGui::SliderInt("roots", &s.roots.count, 100, 100000, "%d", ImGuiSliderFlags_Logarithmic);
  changed |= ImGui::IsItemDeactivatedAfterEdit();
  float length = static_cast<float>(s.growth.max_length);
  ImGui::SliderFloat("max length (d)", &length, 5, 400);
  if (ImGui::IsItemDeactivatedAfterEdit()) s.growth.max_length = length, changed = true;
  if (ImGui::Checkbox("scalp avoidance (thesis 4.6)", &s.scalp_avoidance)) changed = true;
  // The gravity prior (gravity_prior.h): 0 is the thesis' field.
  float prior = static_cast<float>(s.gravity_prior.strength);
  ImGui::SliderFloat("gravity prior", &prior, 0, 1, prior == 0 ? "off" : "%.2f");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("where nothing is sketched, hair leaves the scalp and falls (0: the thesis' field)");
  if (ImGui::IsItemDeactivatedAfterEdit()) s.gravity_prior.strength = prior, changed = true;
  // Field detail (thesis 4.7, Eq. 4.1 with δ from the wavy example): 0 is the smooth field.
  float wave_amplitude = static_cast<float>(s.field_detail.amplitude),
        wave_length = static_cast<float>(s.field_detail.wavelength);
  ImGui::SliderFloat("field waves", &wave_amplitude, 0, 1, "%.2f");
  if (ImGui::IsItemDeactivatedAfterEdit()) s.field_detail.amplitude = wave_amplitude, changed = true;
  ImGui::SliderFloat("wave length", &wave_length, 0.1f, 2, "%.2f");
  if (ImGui::IsItemDeactivatedAfterEdit()) s.field_detail.wavelength = wave_length, changed = true;
  if (changed) {
    execute(v, Command{"change settings", SetSettings{s}, std::nullopt});
    settings_changed();
  }
  ImGui::Separator();
  int drawn = static_cast<int>(strand_budget_.value());
  const bool budget_set = ImGui::SliderInt("drawn segments", &drawn, 0, 4000000, drawn == 0 ? "all" : "%d");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("segments of strands drawn (0: all); adapts to the frame time until you set it");
  if (budget_set) strand_budget_.pin(drawn);
  int look = strand_look_ == StrandLook::Ribbons ? 0 : 1;
  const bool look_set = ImGui::Combo("strands as", &look, "ribbons\0lines\0");
  if (look_set) strand_look_ = look == 0 ? StrandLook::Ribbons : StrandLook::Lines;
  const bool shadow_set = ImGui::Checkbox("self-shadowing", &self_shadowing_);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("strands under other hair get less light (density-based occlusion)");
  if (ImGui::ColorEdit3("root colour", root_color_.data()) | ImGui::ColorEdit3("tip colour", tip_color_.data()) |
      ImGui::SliderFloat("strand width", &strand_width_, 0.5f, 4.0f) | budget_set | look_set | shadow_set) {
    redraw_strands(v);
    head_dirty_ = true;  // the scalp under the hair takes the root colour
  }
  if (ImGui::Checkbox("strands", &show_strands_))
    v.scene().lines["strands"].visible = show_strands_, head_dirty_ = true;
  ImGui::SameLine();
  if (ImGui::Checkbox("curves", &show_curves_)) curves_dirty_ = true;
  ImGui::SameLine();
  if (ImGui::Checkbox("scalp", &show_scalp_)) head_dirty_ = true;
  if (ImGui::Checkbox("field glyphs (slice)", &show_glyphs_)) update_glyph_item(v);
  ImGui::End();
}

void HairSketchApp::draw_file_panel(viewer::Viewer& v, viewer::PanelColumn& column) {
  column.begin("Files");
  static char path[512] = "";
  if (!path[0]) std::snprintf(path, sizeof path, "%s", paths_.session.string().c_str());
  ImGui::InputText("session", path, sizeof path);
  paths_.session = path;
  if (ImGui::Button("Save (Ctrl+S)")) save(v, paths_.session);
  ImGui::SameLine();
  if (ImGui::Button("Open (Ctrl+O)")) load(v, paths_.session);
  if (ImGui::Button("Export .hair + .obj (Ctrl+E)")) export_strands(v);
  if (ImGui::Button("Screenshot")) v.request_screenshot(v.screenshot_path());
  column.end();
}

void HairSketchApp::draw_overlay(viewer::Viewer& v) {
  v.overlay(std::string("tool: ") + tool_name(tool_) +
            (selected_ >= 0 ? "  (curve " + std::to_string(selected_) + ")" : ""));
  if (tool_ == Tool::Ponytail) {
    static const char* steps[] = {"draw the spine from the head", "draw the cross section around the spine",
                                  "draw the first profile", "draw the second profile"};
    v.overlay("ponytail " + std::to_string(ponytail_strokes_.size() + 1) +
              "/4: " + steps[std::min<size_t>(3, ponytail_strokes_.size())]);
  }
  if (last_) {
    char buf[256];
    const LiveUpdate& u = last_->update;
    std::snprintf(buf, sizeof buf, "%d strands, %d segments, %lld unknowns", u.strands.count(), u.strands.segments(),
                  static_cast<long long>(last_->grid.num_nodes()));
    v.overlay(buf);
    std::snprintf(buf, sizeof buf, "last update: solve %.0f ms + growth %.0f ms + detail %.0f ms = %.0f ms (%s)",
                  u.solve_ms, u.growth_ms, u.detail_ms, u.total_ms,
                  u.solves.empty() ? "-" : to_string(u.solves.front().method));
    v.overlay(buf);
  }
  if (!edits_.empty()) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "edit to strands: %.0f ms", edits_.back().total_ms);
    v.overlay(buf);
  }
  if (last_ && shown_strands_ < last_->update.strands.count()) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "drawing %d of %d strands (panel: drawn segments)", shown_strands_,
                  last_->update.strands.count());
    v.overlay(buf);
  }
  if (busy()) v.overlay("regrowing...");
  if (!engine_error_.empty()) v.overlay("error: " + engine_error_);
}

}  // namespace lapis::hair_app
