// The deform app's Dear ImGui panels: tools and paint targets (the salient features among
// them), method and its options, the active handle's exact transform, files, the distortion
// legend and the timing overlay.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "deform_app.h"
#include "lapis/geometry/polar.h"
#include "lapis/viewer/colormap.h"
#include "lapis/viewer/gizmo.h"
#include "lapis/viewer/panel_column.h"
#include "lapis/viewer/tone.h"

namespace lapis::deform_app {
namespace {

ImVec4 to_imvec(const Eigen::Vector3f& c) { return ImVec4(c.x(), c.y(), c.z(), 1.0f); }

// A greyed hint (key bindings, what a control does), wrapped at the panel's edge.
void hint(const char* text) {
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
  ImGui::TextWrapped("%s", text);
  ImGui::PopStyleColor();
}

// The active handle's transform as the panel edits it: a uniform scale and a rotation about
// the handle's rest centroid c, then a translation of c (x' = t + c + s R (x − c)).
struct HandlePose {
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  Eigen::Vector3d euler_deg = Eigen::Vector3d::Zero();  // about x, then y, then z (R = Rz Ry Rx)
  double scale = 1;
};

HandlePose decompose(const Eigen::Matrix4d& T, const Eigen::Vector3d& c) {
  HandlePose p;
  const Eigen::Matrix3d L = T.topLeftCorner<3, 3>();
  p.scale = std::cbrt(std::abs(L.determinant()));
  const Eigen::Matrix3d R = geometry::polar_rotation(L / std::max(p.scale, 1e-12));
  // R = Rz(c) Ry(b) Rx(a) with b in [-90°, 90°]: small turns read as small angles (Eigen's
  // eulerAngles() would give 180, -180, 141 for a 39° turn about z).
  const double ry = std::asin(std::clamp(-R(2, 0), -1.0, 1.0));
  const double rx = std::atan2(R(2, 1), R(2, 2)), rz = std::atan2(R(1, 0), R(0, 0));
  p.euler_deg = (Eigen::Vector3d(rx, ry, rz) * 180 / std::numbers::pi).array() + 0.0;  // + 0: no "-0.0" shown
  p.translation = L * c + T.topRightCorner<3, 1>() - c;
  return p;
}

Eigen::Matrix4d compose(const HandlePose& p, const Eigen::Vector3d& c) {
  const Eigen::Vector3d a = p.euler_deg * std::numbers::pi / 180;
  const Eigen::Matrix3d R =
      (Eigen::AngleAxisd(a.z(), Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(a.y(), Eigen::Vector3d::UnitY()) *
       Eigen::AngleAxisd(a.x(), Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = p.scale * R;
  T.topRightCorner<3, 1>() = p.translation + c - p.scale * R * c;
  return T;
}

}  // namespace

void DeformApp::on_gui(viewer::Viewer& v) {
  // The Selection, Method and Handle panels down the right edge, each sized to its content.
  viewer::PanelColumn column(static_cast<float>(v.width()), static_cast<float>(v.height()), kPanelWidth, 3);
  draw_tools_panel(v, column);
  draw_method_panel(column);
  draw_handle_panel(column);
  draw_file_panel(v);
  draw_transfer_panel(v);
  draw_legend(v);
  draw_overlay(v);
  draw_roi_warning(v);
  draw_cursor(v);
  draw_leave_prompt(v);
}

void DeformApp::draw_tools_panel(viewer::Viewer& v, viewer::PanelColumn& column) {
  column.begin("Selection");
  // The status first: new handles and warnings below it must not push it out of view.
  if (!selection_error_.empty())  // incomplete, not failed: what to paint next
    viewer::tone_text(viewer::Tone::Warning, selection_error_);
  else if (selection_)
    ImGui::Text("ROI %zu vertices, %zu handle(s)", selection_->selection.roi.size(),
                selection_->selection.region_handles.size());
  for (Tool t : {Tool::Move, Tool::Brush, Tool::Lasso, Tool::Connected, Tool::Geodesic, Tool::Pair}) {
    if (t == Tool::Pair && !pairing_) continue;
    if (t != Tool::Move && t != Tool::Connected) ImGui::SameLine();
    if (ImGui::RadioButton(tool_name(t), tool_ == t)) tool_ = t;
  }
  hint("M move  B brush  L lasso  K connected  G geodesic  Shift: erase");
  if (ImGui::Checkbox("x-ray (X): brush and lasso select through", &xray_)) surface_dirty_ = markers_dirty_ = true;
  if (tool_ == Tool::Connected) ImGui::Checkbox("within the clicked vertex's label", &connected_within_label_);
  if (tool_ == Tool::Geodesic) {
    ImGui::SliderFloat("radius ([ ])", &geodesic_radius_, 0.002f, 1.0f, "%.3f of the diagonal",
                       ImGuiSliderFlags_Logarithmic);
    ImGui::TextDisabled("= %.4g along the surface", geodesic_radius_ * diagonal());
  }
  ImGui::Text("paint:");
  ImGui::SameLine();
  if (ImGui::RadioButton("ROI", target_ == VertexLabels::kRoi)) target_ = VertexLabels::kRoi;
  ImGui::SameLine();
  if (ImGui::RadioButton("fixed", target_ == VertexLabels::kFixed)) target_ = VertexLabels::kFixed;
  ImGui::SameLine();
  if (ImGui::RadioButton("handle", target_ >= 0)) target_ = 0;
  ImGui::SameLine();
  if (ImGui::RadioButton("erase", target_ == VertexLabels::kNone)) target_ = VertexLabels::kNone;
  if (settings_.method == Method::Salient) {
    ImGui::SameLine();
    if (ImGui::RadioButton("feature", target_ == kFeatureTarget)) target_ = kFeatureTarget;
  }
  hint("1 ROI  2 fixed  3 handle  4 erase  N new handle");
  // Handles: pick the active one (the gizmo's and the target's).
  const int handles = state_.labels->handle_count();
  for (int h = 0; h <= std::max(handles - 1, state_.active_handle); ++h) {
    ImGui::PushID(h);
    ImGui::ColorButton("##c", to_imvec(handle_color(h)), ImGuiColorEditFlags_NoTooltip, ImVec2(12, 12));
    ImGui::SameLine();
    const int count = static_cast<int>(state_.labels->with(h).size());
    const std::string label = "handle " + std::to_string(h) + " (" + std::to_string(count) + " vertices)";
    if (ImGui::Selectable(label.c_str(), state_.active_handle == h)) state_.active_handle = h, target_ = 0;
    ImGui::PopID();
  }
  if (ImGui::Button("new handle (N)")) new_handle();
  ImGui::SliderFloat("brush px ([ ])", &brush_px_, 3, 300, "%.0f", ImGuiSliderFlags_Logarithmic);
  if (ImGui::Button("grow (+)")) grow_or_shrink(v, 1);
  ImGui::SameLine();
  if (ImGui::Button("shrink (-)")) grow_or_shrink(v, -1);
  ImGui::SameLine();
  if (ImGui::Button("clear (Del)")) clear_target(v);
  // Symmetry: the target's mirror image across a plane through the bounding box's centre.
  if (ImGui::Button("mirror (Ctrl+M)")) mirror_target(v);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(70);
  ImGui::Combo("##plane", &mirror_choice_, "auto\0x\0y\0z\0");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(90);
  if (ImGui::SliderFloat("tol", &mirror_tolerance_, 0.001f, 0.05f, "%.3f", ImGuiSliderFlags_Logarithmic))
    auto_mirror_axis_ = -1;  // the auto plane is measured with the tolerance
  ImGui::BeginDisabled(!history_.can_undo());
  if (ImGui::Button("undo")) undo(v);
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::BeginDisabled(!history_.can_redo());
  if (ImGui::Button("redo")) redo(v);
  ImGui::EndDisabled();
  ImGui::SameLine();
  if (ImGui::Button("reset pose (R)")) reset_pose(v);
  if (settings_.method == Method::Salient) draw_feature_controls();
  draw_roi_warning_details();
  column.end();
}

namespace {

// The edge-based method's choices (Wang et al.): the domain of its Laplacian, what each cell's
// transform may do, the axes of its scales and the iterations per frame.
void draw_edge_controls(EdgeLaplacianOptions& o) {
  int domain = o.domain == LaplacianDomain::Edges ? 0 : 1;
  if (ImGui::Combo("domain", &domain, "edges (the paper)\0vertices (its baseline)\0"))
    o.domain = domain == 0 ? LaplacianDomain::Edges : LaplacianDomain::Vertices;
  int transform = static_cast<int>(o.transform);
  if (ImGui::Combo("cell transform", &transform, "rotation R1\0isotropic s R1\0anisotropic S R1\0R2 S R1\0"))
    o.transform = static_cast<CellTransform>(transform);
  if (o.transform == CellTransform::AnisotropicScale || o.transform == CellTransform::Full) {
    int frame = o.frame == ScaleFrame::World ? 0 : 1;
    if (ImGui::Combo("scale axes", &frame, "world axes (the paper)\0principal rest axes\0"))
      o.frame = frame == 0 ? ScaleFrame::World : ScaleFrame::RestPrincipal;
  }
  ImGui::SliderInt("iterations / frame", &o.iterations, 1, 20);
  ImGui::Checkbox("warm start from the last frame", &o.warm_start);
}

// The salient method's choices (Zhao et al.): iterations, the subspace's size, detection.
void draw_salient_controls(SalientOptions& o) {
  ImGui::SliderInt("iterations / frame", &o.iterations, 1, 20);
  ImGui::SliderInt("subspace vertices", &o.subspace_vertices, 20, 400);
  ImGui::Checkbox("detect features (HKS)", &o.detect_features);
  if (o.detect_features) ImGui::SliderInt("eigenpairs", &o.detection.hks.eigenpairs, 20, 300);
  ImGui::Checkbox("warm start from the last frame", &o.warm_start);
}

// The isolines model's choices (Au et al.): isolines per handle, Eq. 10 or Eq. 6, the fit of
// each isoline's transform and the iterations a frame may take.
void draw_isolines_controls(IsolinesOptions& o) {
  ImGui::SliderInt("isolines / handle", &o.isolines, 2, 80);
  int solve = o.solve == IsolineSolve::Reduced ? 0 : 1;
  if (ImGui::Combo("iteration", &solve, "Eq. 10 (sampled triangles)\0Eq. 6 (whole mesh)\0"))
    o.solve = solve == 0 ? IsolineSolve::Reduced : IsolineSolve::Full;
  int fit = static_cast<int>(o.fit);
  if (ImGui::Combo("isoline fit", &fit, "rotation\0rotation and scale\0Eq. 9 (the paper)\0"))
    o.fit = static_cast<IsolineFit>(fit);
  ImGui::SliderInt("max iterations", &o.max_iterations, 1, 200);
}

}  // namespace

// The features: pick the one the brush paints (target "feature"; Shift erases), start a new
// one, merge two (§3.1's grouping), or go back to the detected ones.
void DeformApp::draw_feature_controls() {
  ImGui::Separator();
  ImGui::Text("salient features (%d)%s", features_.count, features_edited_ ? ", edited" : "");
  for (int f = 0; f < features_.count; ++f) {
    ImGui::PushID(1000 + f);
    ImGui::ColorButton("##f", to_imvec(feature_color(f)), ImGuiColorEditFlags_NoTooltip, ImVec2(12, 12));
    ImGui::SameLine();
    const std::string label = "feature " + std::to_string(f) + " (" + std::to_string(features_.size_of(f)) + ")";
    if (ImGui::Selectable(label.c_str(), active_feature_ == f)) active_feature_ = f, target_ = kFeatureTarget;
    ImGui::PopID();
  }
  if (ImGui::Button("new feature")) active_feature_ = features_.count, target_ = kFeatureTarget;
  if (features_.count >= 2) {
    ImGui::SameLine();
    ImGui::SetNextItemWidth(60);
    ImGui::InputInt("##from", &merge_from_);
    ImGui::SameLine();
    const bool valid = merge_from_ >= 0 && merge_from_ < features_.count && merge_from_ != active_feature_ &&
                       active_feature_ < features_.count;
    ImGui::BeginDisabled(!valid);
    if (ImGui::Button("merge into active")) {
      features_.merge(active_feature_, merge_from_);
      if (active_feature_ > merge_from_) --active_feature_;
      features_edited_ = true;
      ++features_revision_;
      surface_dirty_ = true;
    }
    ImGui::EndDisabled();
  }
  if (features_edited_ && ImGui::Button("detected features")) {
    features_edited_ = false;
    ++features_revision_;
  }
}

void DeformApp::draw_method_panel(viewer::PanelColumn& column) {
  column.begin("Method");
  MethodSettings s = settings_;
  const auto& list = methods();
  if (ImGui::BeginCombo("method", method_info(s.method).label)) {
    for (const MethodInfo& m : list)
      if (ImGui::Selectable(m.label, m.method == s.method)) s.method = m.method;
    ImGui::EndCombo();
  }
  if (s.method != Method::Arap && s.method != Method::Salient && s.method != Method::Isolines) {  // cotangents only
    LaplacianWeights& weights = s.method == Method::Edge ? s.edge.weights : s.weights;
    int w = weights == LaplacianWeights::Cotangent ? 0 : 1;
    if (ImGui::Combo("weights", &w, "cotangent\0uniform\0"))
      weights = w == 0 ? LaplacianWeights::Cotangent : LaplacianWeights::Uniform;
  }
  if (s.method == Method::Implicit) {
    ImGui::Checkbox("feature scaling (Eq. 2.11)", &s.scale_features);
    int mode = preview_while_dragging_ ? 0 : 1;
    if (ImGui::Combo("while dragging", &mode, "first system (preview)\0full pipeline every frame\0"))
      preview_while_dragging_ = mode == 0;
  }
  if (s.method == Method::Arap) {
    ImGui::SliderInt("iterations / frame", &s.arap_iterations, 1, 50);
  }
  if (s.method == Method::Edge) draw_edge_controls(s.edge);
  if (s.method == Method::Salient) draw_salient_controls(s.salient);
  if (s.method == Method::Isolines) {
    draw_isolines_controls(s.isolines);
    int mode = preview_while_dragging_ ? 0 : 1;
    if (ImGui::Combo("while dragging", &mode, "every 8th vertex (preview)\0every vertex every frame\0"))
      preview_while_dragging_ = mode == 0;
  }
  if (!(s == settings_)) settings_ = s;  // the next request sets up again
  ImGui::Separator();
  // Distortion fields first (their order is DistortionField's), then the salient and the
  // isolines methods' views.
  constexpr int kFields = 3, kSaliency = 1 + kFields, kField = 2 + kFields, kRigidity = 3 + kFields;
  int mode = color_mode_ == ColorMode::Selection      ? 0
             : color_mode_ == ColorMode::Distortion   ? 1 + static_cast<int>(field_)
             : color_mode_ == ColorMode::Saliency     ? kSaliency
             : color_mode_ == ColorMode::IsolineField ? kField
                                                      : kRigidity;
  if (ImGui::Combo("colour (C)", &mode,
                   "selection\0edge-length ratio\0angle distortion\0Laplacian magnitude ratio\0saliency (salient)\0"
                   "isolines: field φ\0isolines: rigidity ψ\0")) {
    color_mode_ = mode == 0           ? ColorMode::Selection
                  : mode <= kFields   ? ColorMode::Distortion
                  : mode == kSaliency ? ColorMode::Saliency
                  : mode == kField    ? ColorMode::IsolineField
                                      : ColorMode::Rigidity;
    if (color_mode_ == ColorMode::Distortion) field_ = static_cast<DistortionField>(mode - 1);
    surface_dirty_ = markers_dirty_ = true;
  }
  if (color_mode_ == ColorMode::Distortion) {
    // A fixed range keeps the colours comparable between frames and methods; it starts at the
    // range on screen.
    if (ImGui::Checkbox("fixed range", &legend_fixed_)) {
      if (legend_fixed_ && !(legend_max_ > 0)) legend_max_ = static_cast<float>(std::max(legend_hi_, 1e-6));
      update_legend(last_ ? last_->frame.distortion : Eigen::VectorXd());
      surface_dirty_ = true;
    }
    if (legend_fixed_) {
      ImGui::SameLine();
      ImGui::SetNextItemWidth(90);
      if (ImGui::DragFloat("max", &legend_max_, std::max(legend_max_ * 0.01f, 1e-6f), 1e-6f, 1e6f, "%.3g",
                           ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp)) {
        update_legend(Eigen::VectorXd());
        surface_dirty_ = true;
      }
    }
  }
  if ((color_mode_ == ColorMode::IsolineField || color_mode_ == ColorMode::Rigidity) && isolines_.empty())
    ImGui::TextDisabled("(the isolines method's setup shows them)");
  if (ImGui::Checkbox("degenerate vertices", &show_degenerate_)) markers_dirty_ = true;
  column.end();
}

void DeformApp::draw_handle_panel(viewer::PanelColumn& column) {
  if (!selection_ || !state_.labels->any(state_.active_handle)) return;
  column.begin("Handle transform");
  const Eigen::Vector3d c = handle_rest_centroid(state_.active_handle);
  HandlePose p = decompose(active_transform(), c);
  bool changed = false, released = false;
  changed |=
      ImGui::DragScalarN("move", ImGuiDataType_Double, p.translation.data(), 3, 0.002f, nullptr, nullptr, "%.4g");
  released |= ImGui::IsItemDeactivatedAfterEdit();
  changed |=
      ImGui::DragScalarN("rotate (deg)", ImGuiDataType_Double, p.euler_deg.data(), 3, 0.5f, nullptr, nullptr, "%.1f");
  released |= ImGui::IsItemDeactivatedAfterEdit();
  const double lo = 0.05, hi = 20;
  changed |= ImGui::DragScalar("scale", ImGuiDataType_Double, &p.scale, 0.005f, &lo, &hi, "%.3f");
  released |= ImGui::IsItemDeactivatedAfterEdit();
  if (changed) active_transform() = compose(p, c);
  if (released) commit("edit handle " + std::to_string(state_.active_handle));
  hint("gizmo: arrows move, rings rotate, square scales");
  column.end();
}

void DeformApp::draw_file_panel(viewer::Viewer& v) {
  ImGui::SetNextWindowPos(ImVec2(10, static_cast<float>(v.height()) - 230), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(380, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("File");
  if (!paths_.bundled_dir.empty() && ImGui::BeginCombo("bundled mesh", paths_.mesh.filename().string().c_str())) {
    std::vector<fs::path> meshes;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(paths_.bundled_dir, ec)) {
      const std::string ext = e.path().extension().string();
      if (ext == ".off" || ext == ".obj" || ext == ".ply" || ext == ".stl") meshes.push_back(e.path());
    }
    std::sort(meshes.begin(), meshes.end());
    for (const auto& m : meshes)
      if (ImGui::Selectable(m.filename().string().c_str(), m == paths_.mesh)) open_mesh_or_ask(v, m);
    ImGui::EndCombo();
  }
  // The fields start as the mesh's own files (paths_beside) and follow it when another opens.
  ImGui::PushItemWidth(220);
  ImGui::InputText("ROI file", roi_field_.data(), roi_field_.size());
  ImGui::InputText("handles file", handles_field_.data(), handles_field_.size());
  ImGui::InputText("export .obj/.ply", export_field_.data(), export_field_.size());
  ImGui::PopItemWidth();
  paths_.roi = roi_field_.data(), paths_.handles = handles_field_.data(), paths_.export_mesh = export_field_.data();
  if (ImGui::Button("save selection (Ctrl+S)")) save_selection(v);
  ImGui::SameLine();
  if (ImGui::Button("open selection (Ctrl+O)")) load_selection(v);
  if (ImGui::Button("export (Ctrl+E)")) export_result(v);
  ImGui::SameLine();
  if (ImGui::Button("screenshot (Ctrl+P)")) v.request_screenshot(v.screenshot_path());
  ImGui::TextDisabled("screenshot: %s", v.screenshot_path().string().c_str());
  ImGui::End();
}

// Deformation transfer: the target mesh, one row per source handle to place on it, the result.
void DeformApp::draw_transfer_panel(viewer::Viewer& v) {
  // Below the overlay's lines; its rows come and go with the handles, so it sizes itself.
  ImGui::SetNextWindowPos(ImVec2(10, 160), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowCollapsed(!pairing_, ImGuiCond_FirstUseEver);
  ImGui::Begin("Transfer (Au et al. 2007)", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  ImGui::PushTextWrapPos(340);
  ImGui::PushItemWidth(240);
  static char target[512] = "";
  if (!target[0] && !target_path_.empty()) std::snprintf(target, sizeof target, "%s", target_path_.string().c_str());
  ImGui::InputText("target mesh", target, sizeof target);
  if (ImGui::Button("open target")) open_transfer_target(v, target);
  auto end = [] {
    ImGui::PopItemWidth();
    ImGui::PopTextWrapPos();
    ImGui::End();
  };
  if (!pairing_) {
    ImGui::TextDisabled("carry this mesh's deformation onto another one");
    return end();
  }
  ImGui::SameLine();
  if (ImGui::Button("close target")) return close_transfer_target(v), end();
  ImGui::SameLine();
  if (ImGui::Checkbox("show", &show_target_)) target_dirty_ = true;
  ImGui::Text("%s, %d vertices", target_path_.filename().string().c_str(), pairing_->target().num_vertices());
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
  ImGui::TextWrapped("pair tool (P): click where each one is on the target, a click per part");
  ImGui::PopStyleColor();
  for (size_t k = 0; k < pairing_->slots().size(); ++k) {
    const PairSlot& s = pairing_->slots()[k];
    ImGui::PushID(static_cast<int>(k));
    ImGui::ColorButton("##c", to_imvec(s.label < 0 ? fixed_color() : handle_color(s.label)),
                       ImGuiColorEditFlags_NoTooltip, ImVec2(12, 12));
    ImGui::SameLine();
    const std::string clicks = std::to_string(s.seeds.size()) + " of " + std::to_string(s.parts()) + " part(s) placed";
    const std::string status = !s.problem.empty() ? s.problem
                               : !s.placed()      ? clicks + ", click on the target"
                                                  : std::to_string(s.region.size()) + " vertices";
    const std::string row = s.name + ": " + status;
    if (ImGui::Selectable(row.c_str(), active_pair_ == static_cast<int>(k))) {
      active_pair_ = static_cast<int>(k);
      tool_ = Tool::Pair;
    }
    ImGui::PopID();
  }
  if (pairing_->slots().empty()) ImGui::TextDisabled("paint a handle on the mesh first");
  if (!transfer_error_.empty()) {
    viewer::tone_text(viewer::Tone::Error, transfer_error_);
  } else if (transferred_) {
    ImGui::Text("transfer %.0f ms, Eq. 11 residual %.2g, Eq. 12 %.2g", transferred_->ms,
                transferred_->report.eq11_residual, transferred_->report.eq12_residual);
  } else if (pairing_->complete()) {
    ImGui::TextDisabled("transferring after the next solve ...");
  }
  end();
}

void DeformApp::draw_legend(viewer::Viewer& v) {
  if (color_mode_ != ColorMode::Distortion) return;
  ImGui::SetNextWindowPos(ImVec2(10, static_cast<float>(v.height()) - 330), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.6f);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                 ImGuiWindowFlags_NoInputs | ImGuiWindowFlags_NoSavedSettings |
                                 ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav;
  ImGui::Begin("##legend", nullptr, flags);
  ImGui::Text("%s distortion", to_string(field_));
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const float width = 240, height = 14;
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const int steps = 24;
  for (int k = 0; k < steps; ++k) {
    const Eigen::Vector3f a = viewer::colormap(double(k) / steps), b = viewer::colormap(double(k + 1) / steps);
    const ImU32 ca = ImGui::GetColorU32(to_imvec(a)), cb = ImGui::GetColorU32(to_imvec(b));
    draw->AddRectFilledMultiColor(ImVec2(origin.x + width * k / steps, origin.y),
                                  ImVec2(origin.x + width * (k + 1) / steps, origin.y + height), ca, cb, cb, ca);
  }
  ImGui::Dummy(ImVec2(width, height));
  const char* unit = field_ == DistortionField::Angle ? " rad" : "";
  ImGui::Text("0%s", unit);
  ImGui::SameLine(width - 70);
  ImGui::Text("%.3g%s (%s)", legend_hi_, unit, legend_fixed_ ? "fixed" : "p95");
  if (!last_ || last_->frame.distortion.size() == 0) ImGui::TextDisabled("(after the next solve)");
  ImGui::End();
}

void DeformApp::draw_overlay(viewer::Viewer& v) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "%d vertices, tool: %s%s", rest_.num_vertices(), tool_name(tool_),
                xray_ ? ", x-ray: brush and lasso select through" : "");
  v.overlay(buf);
  if (last_) {
    const LiveFrame& f = last_->frame;
    std::snprintf(buf, sizeof buf, "%s: solve %.1f ms%s (setup %.0f ms)", f.method.c_str(), f.solve_ms,
                  f.preview ? " [first system]" : "", f.setup_ms);
    v.overlay(buf);
    if (!f.timing.empty()) v.overlay("  " + f.timing);
    if (!f.degenerate_vertices.empty())
      v.overlay(std::to_string(f.degenerate_vertices.size()) + " degenerate vertices (red points)");
  }
  if (setup_started_ >= 0 && now_ - setup_started_ > 0.2) {
    // The setup runs on the worker: say so, with an indeterminate bar that keeps moving.
    std::snprintf(buf, sizeof buf, "setting up %s ... %.1f s", method_info(settings_.method).name,
                  now_ - setup_started_);
    v.overlay(buf);
    ImGui::SetNextWindowPos(ImVec2(static_cast<float>(v.width()) * 0.5f - 150, 12), ImGuiCond_Always);
    ImGui::SetNextWindowBgAlpha(0.7f);
    ImGui::Begin("##progress", nullptr,
                 ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoInputs |
                     ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing);
    ImGui::Text("%s", buf);
    ImGui::ProgressBar(static_cast<float>(std::fmod(now_ - setup_started_, 1.0)), ImVec2(300, 8), "");
    ImGui::End();
  } else if (worker_.busy()) {
    v.overlay("solving...");
  }
  if (!convergence_.empty()) v.overlay(convergence_);
  if (preview_gap_ >= 0 && !dragging_) {
    std::snprintf(buf, sizeof buf,
                  "on release: up to %.2g%% of the diagonal from the drag's preview (first system, §2.5)",
                  100 * preview_gap_);
    v.overlay(buf);
  }
  if (!engine_error_.empty()) v.overlay("error: " + engine_error_, viewer::Tone::Error);
  if (!selection_error_.empty()) v.overlay("selection: " + selection_error_, viewer::Tone::Warning);
  if (pending_export_) v.overlay("export waits for the solve", viewer::Tone::Warning);
}

void DeformApp::draw_cursor(viewer::Viewer& v) {
  // Not over a panel, where a click goes to the panel, not the brush.
  if (tool_ != Tool::Brush || dragging_ || ImGui::IsWindowHovered(ImGuiHoveredFlags_AnyWindow)) return;
  const Eigen::Vector2d p = v.cursor();
  ImGui::GetForegroundDrawList()->AddCircle(ImVec2(static_cast<float>(p.x()), static_cast<float>(p.y())), brush_px_,
                                            IM_COL32(255, 255, 255, 160), 48, 1.5f);
}

}  // namespace lapis::deform_app
