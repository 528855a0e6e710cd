// lapis-merge's optimal-boundary mode (thesis §3.4): the three regions painted with the brush,
// the band's parameterization placed on the target region's in a 2D view (drag moves it, the
// wheel scales it, right-drag turns it), and the search plus the merge along its boundary on the
// worker, with the iteration's progress in the overlay.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numbers>

#include "merge_app.h"

namespace lapis::merge_app {
namespace {

// ASCII: the panel font has no Greek letters.
const char* kRegionNames[] = {"rough region (source)", "feature (source)", "target region"};

}  // namespace

const char* optimal_region_name(int region) { return kRegionNames[std::clamp(region, 0, 2)]; }

bool MergeApp::optimal_mode() const { return setup().options.mode == mesh_merge::MergeMode::OptimalBoundary; }

std::vector<int>& MergeApp::region_of(MergeSetup& s, int region) {
  return region == 0 ? s.optimal.rough : region == 1 ? s.optimal.feature : s.optimal.target;
}

// A stroke edits the chosen region in place: it starts from the region, on its mesh.
void MergeApp::begin_region_stroke() {
  MergeSetup s = setup();
  painted_ = region_of(s, optimal_region_);
  painted_on_source_ = optimal_region_ != 2;
  paint_mesh_chosen_ = true;
}

void MergeApp::end_region_stroke(viewer::Viewer& v) {
  MergeSetup next = setup();
  std::vector<int>& region = region_of(next, optimal_region_);
  if (region == painted_) return;
  region = painted_;
  commit(v, std::move(next), std::string("paint ") + kRegionNames[optimal_region_]);
}

// The optimizer for the current meshes and regions, built when they change (its set-up fills
// ∂Ωf and solves both conformal maps); null with optimizer_.error set when the regions are not
// valid yet.
std::shared_ptr<const mesh_merge::BoundaryOptimizer> MergeApp::optimizer() {
  const MergeSetup& s = setup();
  OptimizerCache& c = optimizer_;
  if (c.source == s.source && c.target == s.target && c.placement == s.placement && c.rough == s.optimal.rough &&
      c.feature == s.optimal.feature && c.region == s.optimal.target)
    return c.optimizer;
  c = {};
  c.source = s.source, c.target = s.target, c.placement = s.placement;
  c.rough = s.optimal.rough, c.feature = s.optimal.feature, c.region = s.optimal.target;
  if (s.optimal.feature.empty()) return c.error = "paint the feature region first", nullptr;
  try {
    c.optimizer = std::make_shared<const mesh_merge::BoundaryOptimizer>(mesh_merge::placed_source(s), *s.target,
                                                                        mesh_merge::boundary_regions(s));
    c.suggested = c.optimizer->suggested_placement();
  } catch (const Error& e) {
    c.error = e.what();
  }
  return c.optimizer;
}

mesh_merge::Placement2D MergeApp::current_placement() {
  if (setup().optimal.placement) return *setup().optimal.placement;
  optimizer();
  return optimizer_.suggested;
}

std::string MergeApp::edit_optimal(MergeSetup& next) {
  ImGui::Separator();
  ImGui::TextUnformatted("regions (tool 5 paints the chosen one; R):");
  for (int r = 0; r < 3; ++r)
    if (ImGui::RadioButton(kRegionNames[r], optimal_region_ == r)) optimal_region_ = r, tool_ = Tool::Paint;
  ImGui::Text("painted: rough %zu, feature %zu, target %zu vertices", next.optimal.rough.size(),
              next.optimal.feature.size(), next.optimal.target.size());
  ImGui::TextDisabled("empty rough / target region: the whole mesh");
  std::string edit;
  bool hold = next.options.hold_feature;
  if (ImGui::Checkbox("hold the feature's shape (3.5)", &hold))
    next.options.hold_feature = hold, edit = hold ? "hold feature" : "free feature";
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "The feature shares one deformation gradient (thesis 3.5), so it moves by one similarity and only the band "
        "around it bends. Off: it bends with the rest, as thesis 3.4.1 merges.");
  if (ImGui::SmallButton("clear region")) region_of(next, optimal_region_).clear(), edit = "clear region";
  ImGui::SameLine();
  if (ImGui::SmallButton("suggest placement")) next.optimal.placement.reset(), edit = "suggest placement";
  if (!optimizer()) viewer::tone_text(viewer::Tone::Error, optimizer_.error);
  return edit;
}

// The band's normalized parameterization (∂Ω0 and ∂Ωf, placed) over Ω1's (its border), fitted
// to the canvas. Left-drag moves the band, right-drag turns it, the wheel scales it; each
// gesture is one undoable edit.
void MergeApp::draw_placement_window(viewer::Viewer& v) {
  const auto opt = optimizer();
  if (!opt) return;
  ImGui::SetNextWindowPos(ImVec2(10, static_cast<float>(v.height()) - 330), ImGuiCond_FirstUseEver);
  ImGui::Begin("Placement (thesis 3.4)", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  const ImVec2 size(300, 260);
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  ImGui::InvisibleButton("canvas", size, ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight);
  mesh_merge::Placement2D p = placement_drag_ ? *placement_drag_ : current_placement();
  // Canvas frame: Ω1's uv bounding box with a margin.
  const Eigen::MatrixX2d& tuv = opt->target_uv();
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  for (int t : opt->target_faces())
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector2d q = tuv.row(opt->target().F(t, j)).transpose();
      lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
    }
  const double scale = 0.9 * std::min(size.x / (hi - lo).x(), size.y / (hi - lo).y());
  const Eigen::Vector2d mid = 0.5 * (lo + hi);
  auto to_screen = [&](const Eigen::Vector2d& q) {
    return ImVec2(origin.x + size.x / 2 + static_cast<float>(scale * (q.x() - mid.x())),
                  origin.y + size.y / 2 - static_cast<float>(scale * (q.y() - mid.y())));
  };
  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->AddRectFilled(origin, ImVec2(origin.x + size.x, origin.y + size.y), IM_COL32(30, 32, 38, 255));
  const geometry::Connectivity region(geometry::with_faces(opt->target(), opt->target_faces()));
  for (const auto& loop : region.boundary_loops())
    for (size_t i = 0; i < loop.size(); ++i)
      draw->AddLine(to_screen(tuv.row(loop[i])), to_screen(tuv.row(loop[(i + 1) % loop.size()])),
                    IM_COL32(158, 174, 199, 255), 2.0f);
  const Eigen::MatrixX2d& suv = opt->source_uv();
  auto band_loop = [&](const std::vector<int>& loop, ImU32 color) {
    for (size_t i = 0; i < loop.size(); ++i)
      draw->AddLine(to_screen(p(suv.row(loop[i]).transpose())),
                    to_screen(p(suv.row(loop[(i + 1) % loop.size()]).transpose())), color, 2.0f);
  };
  band_loop(opt->outer_loop(), IM_COL32(230, 184, 133, 255));
  band_loop(opt->inner_loop(), IM_COL32(217, 64, 89, 255));
  if (shown_ && shown_->boundary) band_loop(shown_->boundary->loop, IM_COL32(120, 230, 120, 255));
  // Gestures, about the band's image centre.
  const ImGuiIO& io = ImGui::GetIO();
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (int w : opt->outer_loop()) centre += p(suv.row(w).transpose());
  centre /= static_cast<double>(opt->outer_loop().size());
  bool changed = false;
  if (ImGui::IsItemActive() && (io.MouseDelta.x != 0 || io.MouseDelta.y != 0)) {
    if (!placement_drag_) placement_drag_ = p;
    if (ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
      placement_drag_->offset += Eigen::Vector2d(io.MouseDelta.x, -io.MouseDelta.y) / scale;
    } else {
      const double turn = io.MouseDelta.x * 0.01;
      const Eigen::Rotation2Dd R(turn);
      placement_drag_->angle += turn;
      placement_drag_->offset = centre + R * (placement_drag_->offset - centre);
    }
  }
  if (placement_drag_ && !ImGui::IsItemActive()) changed = true;
  if (ImGui::IsItemHovered() && io.MouseWheel != 0) {
    const double f = std::pow(1.1, io.MouseWheel);
    p.scale *= f, p.offset = centre + f * (p.offset - centre);
    placement_drag_ = p, changed = true;
  }
  ImGui::Text("scale %.3f, %.1f deg, offset (%.3f, %.3f)", p.scale, p.angle * 180 / std::numbers::pi, p.offset.x(),
              p.offset.y());
  ImGui::TextDisabled("drag: move, right-drag: turn, wheel: scale");
  ImGui::End();
  if (changed) {
    MergeSetup next = setup();
    next.optimal.placement = *placement_drag_;
    placement_drag_.reset();
    commit(v, std::move(next), "place band");
  }
}

// The worker's job in optimal mode: the search (progress into the shared counters), then the
// merge along the boundary found.
void MergeApp::run_optimal(MergeOutcome& out, const MergeSetup& s,
                           const std::shared_ptr<const mesh_merge::BoundaryOptimizer>& opt, const std::string& error,
                           const mesh_merge::Placement2D& placement, const std::shared_ptr<OptimalProgress>& progress) {
  if (!opt) throw InvalidArgument(error);
  progress->iteration = 0;
  out.boundary = opt->optimize(placement, [&](int k, const mesh_merge::BoundaryIteration& it) {
    progress->iteration = k + 1;
    progress->energy = it.energy;
  });
  out.result = opt->merge(*out.boundary, s.options);
  out.quality = mesh_merge::seam_quality(*s.target, out.result);
  out.detail = mesh_merge::detail_preservation(opt->source(), out.result);
  out.feature_distortion = mesh_merge::feature_distortion(
      opt->source(), out.result, geometry::vertices_of_faces(opt->source(), opt->feature_faces()));
}

}  // namespace lapis::merge_app
