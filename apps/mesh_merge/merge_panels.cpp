// lapis-merge's Dear ImGui panels: the file menu (bundled meshes and presets), the merge panel
// (tools, pairs, mode, options, Merge) and the result panel (seam quality, timings). Every edit
// goes through an undoable commit; sliders commit when released (one undo step per drag).
#include <imgui.h>

#include <algorithm>

#include "bundled_meshes.h"
#include "lapis/viewer/tone.h"
#include "merge_app.h"

namespace lapis::merge_app {
namespace {

void tooltip(const char* text) {
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) ImGui::SetTooltip("%s", text);
}

const char* kTransitionTooltip =
    "Overlapped transition regions (thesis 3.3.3): a band of each mesh next to the seam (edge-path distance below its "
    "width, in the target's units) overlaps the other's; both deform, their details are tied by E_T (w_T = 0.1) and "
    "interpolated across the band instead of smoothing the seam. Configuration-independent.";
const char* kOptimalTooltip =
    "The optimal merging boundary (thesis 3.4): paint a rough region around the feature to merge and the feature "
    "itself on the source, and a region on the target (tool 5; R picks the region); place the band in the placement "
    "view; M searches "
    "the boundary whose image changes least (Eq. 3.1) and merges along it.";

}  // namespace

void MergeApp::on_gui(viewer::Viewer& v) {
  draw_merge_panel(v);
  if (optimal_mode()) draw_placement_window(v);
  draw_result_panel(v);
  draw_labels(v);
  draw_overlay(v);
}

void MergeApp::draw_menu(viewer::Viewer& v) {
  // In the panel's own menu bar: a main menu bar would sit under the viewer's overlay.
  if (!ImGui::BeginMenuBar()) return;
  if (ImGui::BeginMenu("File")) {
    if (ImGui::BeginMenu("Presets")) {
      for (size_t i = 0; i < preset_names().size(); ++i)
        if (ImGui::MenuItem(preset_names()[i].c_str())) load_preset(v, static_cast<int>(i));
      ImGui::EndMenu();
    }
    for (int side = 0; side < 2; ++side) {
      if (!ImGui::BeginMenu(side == 0 ? "Open source" : "Open target")) continue;
      for (const BundledMesh& m : bundled_meshes(paths_.asset_dir))
        if (ImGui::MenuItem(m.label.c_str())) load_mesh(v, m.path, side == 0);
      ImGui::EndMenu();
    }
    ImGui::Separator();
    if (ImGui::MenuItem("Export merged mesh + pairs", "Ctrl+E")) export_pending_ = true;
    if (ImGui::MenuItem("Screenshot", "Ctrl+P")) v.request_screenshot(v.screenshot_path());
    if (ImGui::MenuItem("Quit", "Ctrl+Q")) v.close();
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Edit")) {
    if (ImGui::MenuItem("Undo", "Ctrl+Z", false, history_.can_undo())) undo(v);
    if (ImGui::MenuItem("Redo", "Ctrl+Shift+Z", false, history_.can_redo())) redo(v);
    ImGui::EndMenu();
  }
  ImGui::EndMenuBar();
}

void MergeApp::draw_merge_panel(viewer::Viewer& v) {
  ImGui::SetNextWindowPos(ImVec2(static_cast<float>(v.width()) - kPanelWidth, 10), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSizeConstraints(ImVec2(kPanelWidth - 8, 0), ImVec2(kPanelWidth - 8, 1e6f));
  ImGui::Begin("Merge", nullptr, ImGuiWindowFlags_MenuBar | ImGuiWindowFlags_AlwaysAutoResize);
  draw_menu(v);
  ImGui::PushItemWidth(150);
  draw_inputs_and_tools(v);
  // Every section draws its widgets each frame; the last edit of the frame names the commit.
  MergeSetup next = setup();
  std::string edit;
  for (std::string e : {edit_pairs(next), edit_mode(next), edit_mode_options(next)})
    if (!e.empty()) edit = std::move(e);
  if (next.options.mode == mesh_merge::MergeMode::OptimalBoundary)
    if (std::string e = edit_optimal(next); !e.empty()) edit = std::move(e);
  if (!edit.empty()) commit(v, std::move(next), edit);
  draw_merge_actions(v);
  ImGui::PopItemWidth();
  merge_panel_bottom_ = ImGui::GetWindowPos().y + ImGui::GetWindowSize().y;
  ImGui::End();
}

void MergeApp::draw_inputs_and_tools(viewer::Viewer& v) {
  ImGui::TextWrapped("source: %s (%d vertices, %zu loops)", source_name().c_str(), source_.mesh.num_vertices(),
                     source_.loops().size());
  ImGui::TextWrapped("target: %s (%d vertices, %zu loops)", target_name().c_str(), target_.mesh.num_vertices(),
                     target_.loops().size());
  ImGui::Separator();
  const Tool tools[] = {Tool::PairLoops, Tool::Keys, Tool::Handles, Tool::Move, Tool::Paint};
  for (int i = 0; i < 5; ++i) {
    if (i % 2) ImGui::SameLine();
    if (ImGui::RadioButton(tool_name(tools[i]), tool_ == tools[i])) tool_ = tools[i], scene_dirty_ = true;
  }
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
  ImGui::TextWrapped("keys 1-5 tools, D dependent, T transition, M merge, Tab result/inputs");
  ImGui::PopStyleColor();
  if (tool_ == Tool::Paint) draw_paint_controls(v);
}

// The pairs, with their keys; x removes a pair, -key its last key.
std::string MergeApp::edit_pairs(MergeSetup& next) {
  for (size_t p = 0; p < next.pairs.size(); ++p) {
    ImGui::PushID(static_cast<int>(p));
    const auto& pair = next.pairs[p];
    ImGui::Text("pair %zu: loops %d <-> %d, %zu key%s%s", p + 1, pair.source_loop, pair.target_loop, pair.keys.size(),
                pair.keys.size() == 1 ? "" : "s", pair.keys_suggested ? " (suggested)" : "");
    ImGui::SameLine();
    std::string edit;
    if (ImGui::SmallButton("x")) {
      next.pairs.erase(next.pairs.begin() + static_cast<long>(p)), edit = "remove pair";
    } else if (!pair.keys.empty()) {
      ImGui::SameLine();
      if (ImGui::SmallButton("-key")) next.pairs[p].keys.pop_back(), edit = "remove key";
    }
    ImGui::PopID();
    if (!edit.empty()) return edit;
  }
  return {};
}

std::string MergeApp::edit_mode(MergeSetup& next) {
  ImGui::Separator();
  using mesh_merge::MergeMode;
  MergeMode& mode = next.options.mode;
  std::string edit;
  if (ImGui::RadioButton("configuration-independent (thesis 3.3.1)", mode == MergeMode::Independent))
    mode = MergeMode::Independent, edit = "mode";
  if (ImGui::RadioButton("configuration-dependent (thesis 3.3.2)", mode == MergeMode::Dependent))
    mode = MergeMode::Dependent, edit = "mode";
  if (ImGui::RadioButton("transition regions (thesis 3.3.3)", mode == MergeMode::Transition)) {
    mode = MergeMode::Transition, edit = "mode";
    auto& t = next.options.transition;
    if (!(t.source_width > 0) || !(t.target_width > 0))
      t.source_width = t.target_width = first_band_width(next);  // merge_app.h
  }
  tooltip(kTransitionTooltip);
  if (ImGui::RadioButton("optimal boundary (thesis 3.4)", mode == MergeMode::OptimalBoundary))
    mode = MergeMode::OptimalBoundary, edit = "mode";
  tooltip(kOptimalTooltip);
  return edit;
}

// The selected mode's own options, the smoothing, and the placement of the source.
std::string MergeApp::edit_mode_options(MergeSetup& next) {
  using mesh_merge::MergeMode;
  const MergeMode mode = next.options.mode;
  std::string edit;
  if (mode == MergeMode::Transition) edit = edit_transition_bands(next.options.transition);
  if (mode == MergeMode::Independent) {
    // §3.5: painted source regions that keep their shape, each moved by one similarity.
    ImGui::Text("%zu fixed features (3.5)", next.options.features.size());
    tooltip(
        "Fixed features (thesis 3.5): each shares one deformation gradient, so it moves by one similarity while "
        "the rest of the source bends. Paint a region on the source with tool 5, then add it.");
    ImGui::SameLine();
    ImGui::BeginDisabled(!painted_on_source_ || painted_.size() < 4);  // a gradient needs 4 vertices
    if (ImGui::SmallButton("add painted (A)"))
      next.options.features.push_back(painted_), painted_.clear(), edit = "add feature";
    ImGui::EndDisabled();
    ImGui::SameLine();
    if (ImGui::SmallButton("clear##features")) next.options.features.clear(), edit = "clear features";
  }
  const bool placed = mode == MergeMode::Dependent ||
                      (mode == MergeMode::Transition && next.options.transition.configuration_dependent);
  if (placed) {
    float width = static_cast<float>(next.options.roi_width);
    ImGui::SliderFloat("ROI width (0: auto)", &width, 0.0f,
                       static_cast<float>(std::max(1e-3, source_.mesh.V.colwise().maxCoeff().maxCoeff() -
                                                             source_.mesh.V.colwise().minCoeff().minCoeff())));
    if (ImGui::IsItemDeactivatedAfterEdit()) next.options.roi_width = width, edit = "ROI width";
    ImGui::Text("%zu fixed handles (tool 3: click the source)", next.options.handles.size());
    ImGui::SameLine();
    if (ImGui::SmallButton("clear")) next.options.handles.clear(), edit = "clear handles";
  }
  int smooth = next.options.smooth_iterations;
  // Transition regions replace the seam smoothing (§3.3.3), which the module skips there.
  ImGui::BeginDisabled(mode == MergeMode::Transition);
  ImGui::SliderInt("smoothing iterations", &smooth, 0, 30);
  if (ImGui::IsItemDeactivatedAfterEdit()) next.options.smooth_iterations = smooth, edit = "smoothing";
  ImGui::EndDisabled();
  if (ImGui::Button("place source at the first pair") && !next.pairs.empty()) {
    // The placed source has the rest source's connectivity, so its loops index the rest mesh too.
    next.placement =
        mesh_merge::suggest_placement(*next.source, source_.loops()[static_cast<size_t>(next.pairs[0].source_loop)],
                                      *next.target, target_.loops()[static_cast<size_t>(next.pairs[0].target_loop)]);
    edit = "place source";
  }
  return edit;
}

std::string MergeApp::edit_transition_bands(mesh_merge::TransitionOptions& t) {
  std::string edit;
  float band[2] = {static_cast<float>(t.source_width), static_cast<float>(t.target_width)};
  const float most = static_cast<float>(std::max(1e-3, 0.5 * mesh_merge::bbox_diagonal(target_.mesh.V)));
  ImGui::SliderFloat2("widths", band, 1e-3f * most, most);
  tooltip(kTransitionTooltip);
  if (ImGui::IsItemDeactivatedAfterEdit()) t.source_width = band[0], t.target_width = band[1], edit = "band widths";
  int keep = t.keep == mesh_merge::TransitionKeep::Source ? 0 : 1;
  ImGui::TextUnformatted("band connectivity:");
  ImGui::SameLine();
  if (ImGui::RadioButton("source's", keep == 0)) keep = 0, edit = "band connectivity";
  ImGui::SameLine();
  if (ImGui::RadioButton("target's", keep == 1)) keep = 1, edit = "band connectivity";
  t.keep = keep == 0 ? mesh_merge::TransitionKeep::Source : mesh_merge::TransitionKeep::Target;
  bool placed = t.configuration_dependent;
  if (ImGui::Checkbox("keep the placement (3.3.2 boundary)", &placed))
    t.configuration_dependent = placed, edit = "transition boundary";
  tooltip(
      "Transition regions on the configuration-dependent boundary condition (thesis 3.3.2): the source stays where "
      "it is placed, only vertices within the ROI width of its rim and the band move, the handles stay fixed.");
  return edit;
}

// Merge, auto-merge, what input is missing, the last error, undo / redo and export.
void MergeApp::draw_merge_actions(viewer::Viewer& v) {
  ImGui::Separator();
  if (!setup().pairs.empty() && ImGui::Button("suggest keys (K)")) suggest_all_keys(v);
  tooltip(
      "A key for every pair from the loops as the source is placed: the turn that brings the two rims closest. "
      "Where the key sits decides which way round the source is merged; move the source (tool 4) and press K "
      "again to turn it.");
  if (ImGui::Button("Merge (M)")) requested_revision_ = 0, request_merge();
  ImGui::SameLine();
  ImGui::Checkbox("auto-merge", &auto_merge_);
  tooltip(
      "Merge after every change while a re-merge (the last merge without its one-off precompute) takes "
      "under 0.5 s.");
  if (auto_merge_ && remerge_ms_ && *remerge_ms_ >= kAutoMergeMs)
    ImGui::TextDisabled("auto-merge paused: a re-merge takes %.2f s", *remerge_ms_ / 1000.0);
  const std::string missing = mesh_merge::missing_input(setup(), static_cast<int>(source_.loops().size()));
  if (!missing.empty()) ImGui::TextWrapped("next: %s", missing.c_str());
  if (last_ && !last_->error.empty()) viewer::tone_text(viewer::Tone::Error, last_->error);
  ImGui::BeginDisabled(!history_.can_undo());
  if (ImGui::Button("Undo")) undo(v);
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::BeginDisabled(!history_.can_redo());
  if (ImGui::Button("Redo")) redo(v);
  ImGui::EndDisabled();
  ImGui::SameLine();
  if (ImGui::Button("Export (Ctrl+E)")) export_pending_ = true;
}

void MergeApp::draw_paint_controls(viewer::Viewer& v) {
  ImGui::SliderFloat("brush (px)", &brush_px_, 4.0f, 80.0f);
  if (ImGui::Checkbox("x-ray (X): paint through the surface", &xray_)) scene_dirty_ = true;
  ImGui::Text("%zu vertices painted on the %s", painted_.size(), painted_on_source_ ? "source" : "target");
  const PickableMesh& m = painted_on_source_ ? source_ : target_;
  if (ImGui::SmallButton("grow")) painted_ = viewer::grow_rings(*m.conn, painted_, 1), scene_dirty_ = true;
  ImGui::SameLine();
  if (ImGui::SmallButton("shrink")) painted_ = viewer::shrink_rings(*m.conn, painted_, 1), scene_dirty_ = true;
  ImGui::SameLine();
  if (ImGui::SmallButton("clear")) painted_.clear(), scene_dirty_ = true;
  ImGui::SameLine();
  if (ImGui::SmallButton("cut (C)")) cut_painted(v);
  ImGui::TextDisabled("source keeps the painted part, target the rest");
}

void MergeApp::draw_result_panel(viewer::Viewer& v) {
  // Under the merge panel, whose height changes with the tool and the mode, and never past the
  // window's bottom (it scrolls there).
  const float top = std::min(merge_panel_bottom_ + 6, static_cast<float>(v.height()) - 40);
  ImGui::SetNextWindowPos(ImVec2(static_cast<float>(v.width()) - kPanelWidth, top), ImGuiCond_Always);
  ImGui::SetNextWindowSizeConstraints(
      ImVec2(kPanelWidth - 8, 0), ImVec2(kPanelWidth - 8, std::max(40.0f, static_cast<float>(v.height()) - top - 10)));
  ImGui::Begin("Result", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  if (!shown_) {
    ImGui::TextDisabled("no merge yet");
    ImGui::End();
    return;
  }
  const auto& r = shown_->result;
  const auto& q = shown_->quality;
  const auto& t = r.timings;
  if (shown_->revision != revision()) viewer::tone_text(viewer::Tone::Warning, "setup changed since this merge");
  ImGui::TextWrapped("%d vertices, %d faces (%zu seam strip faces)", r.mesh.num_vertices(), r.mesh.num_faces(),
                     r.strip_faces.size());
  viewer::tone_text(q.valid() ? viewer::Tone::Success : viewer::Tone::Error,
                    q.valid() ? "seam watertight and manifold" : "seam NOT valid");
  if (const std::string flag = result_flag(); !flag.empty()) viewer::tone_text(viewer::Tone::Error, flag);
  if (shown_->boundary) {
    const mesh_merge::OptimalBoundary& b = *shown_->boundary;
    ImGui::Text("boundary energy %.3g (rough border %.3g)", b.energy, b.user_energy);
    ImGui::Text("  %zu vertices (rough border %zu), %zu iterations: %s", b.loop.size(), b.user_loop.size(),
                b.history.size(), b.stopped_by.c_str());
    ImGui::Text("feature distortion %.2g (%s)", shown_->feature_distortion,
                setup().options.hold_feature ? "held" : "free");
    tooltip("the feature's largest distance from a similar copy of itself, over its size: 0 when it moved rigidly");
  }

  ImGui::Text("seam boundary edges %d, degenerate faces %d", q.seam_boundary_edges, q.degenerate_faces);
  ImGui::Text("non-manifold edges %d, vertices %d", q.non_manifold_edges, q.non_manifold_vertices);
  ImGui::Text("min strip angle %.1f deg", q.min_strip_angle_deg);
  ImGui::Text("seam dihedral mean %.1f / max %.1f deg", q.seam_dihedral_mean_deg, q.seam_dihedral_max_deg);
  ImGui::Text("folded seam edges (over %.0f deg) %d", geometry::kFoldedDihedralDeg, q.folded_seam_edges);
  if (q.inherited_folds > 0) ImGui::Text("  and %d where the target folds already", q.inherited_folds);
  ImGui::Text("target dihedral mean %.1f / p95 %.1f deg", q.target_dihedral_mean_deg, q.target_dihedral_p95_deg);
  ImGui::Text("target moved outside the seam band: %.2g", q.max_target_displacement);
  ImGui::Text("detail: Laplacian residual %.3f", shown_->detail.laplacian_residual);
  ImGui::Text("  max distance after alignment %.3f", shown_->detail.max_distance);
  ImGui::Separator();
  ImGui::Text("precompute %.0f ms%s", shown_->precompute_ms, shown_->reused ? " (earlier, reused)" : "");
  ImGui::Text("merge %.0f ms: setup %.0f, solve %.0f,", t.total_ms, t.setup_ms, t.solve_ms);
  ImGui::Text("  zip %.0f, smooth %.0f", t.zip_ms, t.smooth_ms);
  ImGui::Text("job (with metrics) %.0f ms", shown_->job_ms);
  ImGui::Text("refine levels %d, ROI %d vertices", r.refine_levels, r.roi_vertices);
  bool result = show_result_;
  if (ImGui::Checkbox("show result (Tab)", &result)) show_result_ = result, scene_dirty_ = true;
  ImGui::End();
}

void MergeApp::draw_overlay(viewer::Viewer& v) {
  v.overlay(std::string("tool: ") + tool_name(tool_));
  if (tool_ == Tool::PairLoops) {
    if (pending_source_loop_ >= 0)
      v.overlay("source loop picked: now click a target loop");
    else if (pending_target_loop_ >= 0)
      v.overlay("target loop picked: now click a source loop");
    else
      v.overlay("click a boundary loop of each mesh to pair them");
  } else if (tool_ == Tool::Move) {
    v.overlay("drag an arrow (move), a ring (rotate) or the centre square (scale) to place the source");
  } else if (tool_ == Tool::Paint && optimal_mode()) {
    v.overlay("left-drag paints the chosen region, Shift+drag erases it");
  } else if (tool_ == Tool::Paint) {
    v.overlay(xray_ ? "x-ray: left-drag paints through the surface, back included; Shift+drag erases; C cuts"
                    : "left-drag paints on either mesh, Shift+drag erases; C cuts along the painted border; X: x-ray");
  } else if (tool_ == Tool::Keys) {
    if (pending_key_source_ >= 0)
      v.overlay("source vertex picked: now click a vertex of its paired target loop");
    else if (pending_key_target_ >= 0)
      v.overlay("target vertex picked: now click a vertex of its paired source loop");
    else
      v.overlay("click a vertex on each loop of a pair: a key correspondence");
  }
  if (show_result_ && shown_ && !v.scene().meshes["source"].visible)
    v.overlay("Tab: show the inputs to pick on the source");
  if (worker_.busy() && optimal_mode()) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "optimal boundary: iteration %d, E = %.3g", optimal_progress_->iteration.load(),
                  optimal_progress_->energy.load());
    v.overlay(buf);
  } else if (worker_.busy()) {
    v.overlay("merging...");
  }
  if (shown_) {
    char buf[128];
    std::snprintf(buf, sizeof buf, "last merge %.0f ms (job %.0f ms)", shown_->result.timings.total_ms, shown_->job_ms);
    v.overlay(buf);
    if (const std::string flag = result_flag(); !flag.empty()) v.overlay(flag, viewer::Tone::Error);
  }
}

}  // namespace lapis::merge_app
