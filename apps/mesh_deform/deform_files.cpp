// Where the deform app's files go, and what keeps a user's edits from being lost: the File
// panel's fields, the edits not yet saved, and the prompt before quitting or opening another
// mesh discards them.
#include <imgui.h>
#include <unistd.h>

#include <cstdio>

#include "deform_app.h"

namespace lapis::deform_app {
namespace {

bool inside(const fs::path& file, const fs::path& dir) {
  if (dir.empty()) return false;
  std::error_code ec;
  const fs::path a = fs::weakly_canonical(file.parent_path(), ec), b = fs::weakly_canonical(dir, ec);
  return !ec && a == b;
}

void copy_to(std::array<char, 1024>& field, const fs::path& path) {
  std::snprintf(field.data(), field.size(), "%s", path.string().c_str());
}

}  // namespace

DeformPaths paths_beside(const fs::path& mesh, DeformPaths defaults, const std::string& variant) {
  fs::path dir = mesh.parent_path();
  if (dir.empty()) dir = ".";
  // Bundled meshes are the toolkit's, not the user's: their files go to out/.
  if (inside(mesh, defaults.bundled_dir) || ::access(dir.c_str(), W_OK) != 0) dir = "out";
  const std::string stem = mesh.stem().string() + variant;
  defaults.mesh = mesh;
  defaults.roi = dir / (stem + ".roi.txt");
  defaults.handles = dir / (stem + ".handles.json");
  defaults.export_mesh = dir / (stem + ".deformed.obj");
  defaults.screenshot = dir / (stem + ".screenshot.png");
  return defaults;
}

void DeformApp::fill_file_fields() {
  copy_to(roi_field_, paths_.roi);
  copy_to(handles_field_, paths_.handles);
  copy_to(export_field_, paths_.export_mesh);
}

bool DeformApp::unsaved() const {
  const bool labels = state_.labels != saved_state_.labels && state_.labels->label != saved_state_.labels->label;
  return labels || state_.transforms != saved_state_.transforms;
}

bool DeformApp::may_close(viewer::Viewer&) {
  if (!unsaved()) return true;
  leave_prompt_ = fs::path();
  std::fprintf(stderr, "lapis-deform: unsaved edits: asking before quitting\n");
  return false;
}

void DeformApp::open_mesh_or_ask(viewer::Viewer& v, const fs::path& path) {
  if (!unsaved()) return open_mesh(v, path);
  leave_prompt_ = path;
  std::fprintf(stderr, "lapis-deform: unsaved edits: asking before opening %s\n", path.string().c_str());
}

// A modal: save the selection (its pose included) and go on, go on without saving, or stay.
// Its keys (S, D, Esc) reach the app through on_event wherever the pointer is.
void DeformApp::draw_leave_prompt(viewer::Viewer& v) {
  if (!leave_prompt_) return;
  const bool quit = leave_prompt_->empty();
  ImGui::OpenPopup("Unsaved edits");
  ImGui::SetNextWindowPos(ImVec2(static_cast<float>(v.width()) * 0.5f, static_cast<float>(v.height()) * 0.4f),
                          ImGuiCond_Always, ImVec2(0.5f, 0.5f));
  if (!ImGui::BeginPopupModal("Unsaved edits", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
  ImGui::Text("The selection and pose of %s have edits not saved.", paths_.mesh.filename().string().c_str());
  ImGui::TextDisabled("saving writes %s and %s", paths_.roi.string().c_str(), paths_.handles.string().c_str());
  const std::string go_on = quit ? "quit" : "open " + leave_prompt_->filename().string();
  if (ImGui::Button(("save and " + go_on + " (S)").c_str())) leave(v, LeaveChoice::Save);
  ImGui::SameLine();
  if (ImGui::Button(("discard and " + go_on + " (D)").c_str())) leave(v, LeaveChoice::Discard);
  ImGui::SameLine();
  if (ImGui::Button("cancel (Esc)")) leave(v, LeaveChoice::Stay);
  if (!leave_prompt_) ImGui::CloseCurrentPopup();
  ImGui::EndPopup();
}

void DeformApp::leave(viewer::Viewer& v, LeaveChoice choice) {
  if (!leave_prompt_) return;
  if (choice == LeaveChoice::Save) {
    save_selection(v);
    if (unsaved()) choice = LeaveChoice::Stay;  // the save failed: its message is on screen, nothing is lost
  }
  const fs::path then_open = *leave_prompt_;
  leave_prompt_.reset();
  std::fprintf(stderr, "lapis-deform: unsaved edits: %s\n",
               choice == LeaveChoice::Stay   ? "stayed"
               : choice == LeaveChoice::Save ? "saved"
                                             : "discarded");
  if (choice == LeaveChoice::Stay) return;
  if (then_open.empty())
    v.close();
  else
    open_mesh(v, then_open);
}

}  // namespace lapis::deform_app
