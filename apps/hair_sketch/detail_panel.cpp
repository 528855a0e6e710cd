// The Detail panel and tools: the strand-detail stack (thesis §4.7) as undoable document
// entries, their parameters, a cut line drawn on screen (tool 7) and a region brush that
// paints on the head where the selected detail applies (tool 8).
#include <imgui.h>

#include <string>

#include "hair_sketch_app.h"
#include "lapis/geometry/camera.h"
#include "lapis/viewer/panel_column.h"

namespace lapis::hair_app {
namespace {

// Slider over a double field; true when released after a change (one undo step per drag).
bool slider(const char* label, double& value, float lo, float hi, const char* format = "%.3f") {
  float f = static_cast<float>(value);
  ImGui::SliderFloat(label, &f, lo, hi, format);
  value = f;
  return ImGui::IsItemDeactivatedAfterEdit();
}

bool edit_shape(CurlDetail& c) {
  bool done = slider("turns per unit", c.frequency, 0.5f, 20.f, "%.2f");
  done |= slider("radius", c.radius, 0.f, 0.2f);
  done |= slider("turns growth", c.frequency_growth, -0.9f, 3.f, "%.2f");
  done |= slider("radius growth", c.radius_growth, -1.f, 3.f, "%.2f");
  done |= slider("phase jitter", c.phase_jitter, 0.f, 1.f, "%.2f");
  done |= slider("radius jitter", c.radius_jitter, 0.f, 1.f, "%.2f");
  done |= slider("root fade", c.root_fade, 0.f, 0.5f);
  return done;
}
bool edit_shape(ClumpDetail& c) {
  bool done = ImGui::SliderInt("clumps", &c.clumps, 1, 500), released = ImGui::IsItemDeactivatedAfterEdit();
  (void)done;
  released |= slider("strength", c.strength, 0.f, 1.f, "%.2f");
  released |= slider("profile", c.profile, 0.2f, 5.f, "%.2f");
  return released;
}
bool edit_shape(FrizzDetail& f) {
  bool done = slider("amplitude", f.amplitude, 0.f, 0.05f, "%.4f");
  done |= slider("wavelength", f.wavelength, 0.01f, 0.3f);
  done |= slider("root fade", f.root_fade, 0.f, 0.5f);
  return done;
}
bool edit_shape(LengthDetail& l) { return slider("variation", l.variation, 0.f, 1.f, "%.2f"); }
bool edit_shape(CutDetail& c) {
  ImGui::TextDisabled("a line of %d points, seen as drawn", static_cast<int>(c.line.size()));
  return false;
}

StrandDetail new_detail(int kind, std::uint32_t seed) {
  StrandDetail d;
  d.seed = seed;
  switch (kind) {
    case 0:
      d.shape = CurlDetail{};
      break;
    case 1: {
      CurlDetail wave;
      wave.helical = false;
      wave.frequency = 2;
      wave.radius = 0.05;
      wave.phase_jitter = 0.1;  // neighbours wave together
      d.shape = wave;
      break;
    }
    case 2:
      d.shape = ClumpDetail{};
      break;
    case 3:
      d.shape = FrizzDetail{};
      break;
    default:
      d.shape = LengthDetail{};
  }
  return d;
}

}  // namespace

void HairSketchApp::set_details(viewer::Viewer& v, std::vector<StrandDetail> details, const std::string& name) {
  execute(v, Command{name, SetDetails{std::move(details)}, std::nullopt});
  head_dirty_ = true;
}

void HairSketchApp::add_cut_line(viewer::Viewer& v) {
  if (stroke_.size() < 2) {
    stroke_.clear();
    return v.flash("cut line: drag across the hair where it should end", viewer::Tone::Warning);
  }
  CutDetail cut;
  cut.camera = v.camera_matrices();
  cut.line = std::move(stroke_);
  stroke_.clear();
  std::vector<StrandDetail> details = document_.style().details;
  StrandDetail d;
  d.shape = std::move(cut);
  details.push_back(std::move(d));
  selected_detail_ = static_cast<int>(details.size()) - 1;
  set_details(v, std::move(details), "add cut line");
  update_preview_item(v);
}

void HairSketchApp::paint_region(viewer::Viewer& v, const Eigen::Vector2d& p) {
  // Vertices under the brush that face the camera: the side of the head the user sees.
  const auto cam = v.camera_matrices();
  const Eigen::Vector3d eye = geometry::eye_position(cam);
  const auto& mesh = head_.mesh;
  Eigen::MatrixXd normals = Eigen::MatrixXd::Zero(mesh.num_vertices(), 3);
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) normals.row(mesh.F(f, k)) += head_.face_normals.row(f);
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    const Eigen::Vector3d x = mesh.V.row(i).transpose();
    if (normals.row(i).dot(eye - x) <= 0) continue;
    const Eigen::Vector3d s = geometry::project(cam, x);
    if ((s.head<2>() - p).norm() <= region_brush_pixels_) painted_.insert(i);
  }
  head_dirty_ = true;
}

void HairSketchApp::draw_detail_panel(viewer::Viewer& v, viewer::PanelColumn& column) {
  column.begin("Detail");
  const auto& details = document_.style().details;
  if (details.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped("none: add one below (applied after growth, in order)");
    ImGui::PopStyleColor();
  }
  for (int i = 0; i < static_cast<int>(details.size()); ++i) {
    ImGui::PushID(i);
    std::string label = std::to_string(i) + " " + detail_type(details[i]);
    if (!details[i].region.empty()) label += " (" + std::to_string(details[i].region.size()) + " vertices)";
    if (ImGui::Selectable(label.c_str(), selected_detail_ == i)) {
      selected_detail_ = selected_detail_ == i ? -1 : i;
      head_dirty_ = true;
    }
    ImGui::PopID();
  }
  const char* kinds[] = {"curl", "wave", "clump", "frizz", "length"};
  for (int k = 0; k < 5; ++k) {
    if (k) ImGui::SameLine();
    if (ImGui::SmallButton((std::string("+") + kinds[k]).c_str())) {
      std::vector<StrandDetail> next = details;
      next.push_back(new_detail(k, static_cast<std::uint32_t>(next.size() + 1)));
      selected_detail_ = static_cast<int>(next.size()) - 1;
      set_details(v, std::move(next), std::string("add ") + kinds[k]);
      column.end();
      return;
    }
  }
  if (selected_detail_ >= static_cast<int>(details.size())) selected_detail_ = -1;
  if (selected_detail_ >= 0) {
    ImGui::Separator();
    StrandDetail copy = details[selected_detail_];
    bool commit = std::visit([](auto& shape) { return edit_shape(shape); }, copy.shape);
    int seed = static_cast<int>(copy.seed);
    ImGui::InputInt("seed", &seed);
    if (ImGui::IsItemDeactivatedAfterEdit()) copy.seed = static_cast<std::uint32_t>(std::max(0, seed)), commit = true;
    ImGui::SliderFloat("brush (px)", &region_brush_pixels_, 5, 120, "%.0f");
    ImGui::TextWrapped(copy.region.empty() ? "applies everywhere; tool 8 paints where it applies"
                                           : "applies where painted (orange); tool 8 paints more");
    std::vector<StrandDetail> next = details;
    if (!copy.region.empty() && ImGui::Button("whole scalp")) {
      next[selected_detail_].region.clear();
      set_details(v, std::move(next), "clear detail region");
    } else if (ImGui::Button("remove detail")) {
      next.erase(next.begin() + selected_detail_);
      selected_detail_ = -1;
      set_details(v, std::move(next), "remove detail");
    } else if (commit) {
      next[selected_detail_] = copy;
      set_details(v, std::move(next), std::string("edit ") + detail_type(copy));
    }
  }
  column.end();
}

}  // namespace lapis::hair_app
