// What lapis-merge draws: the target and the (placed) source, the merged result with its source
// part tinted and its seam strips outlined, every boundary loop (paired loops in their pair's
// colour, a half-made pick in yellow), the key correspondences as numbered markers and the
// fixed handles.
#include <imgui.h>

#include "merge_app.h"

namespace lapis::merge_app {
namespace {

const Eigen::Vector3f kTargetColor{0.62f, 0.68f, 0.78f}, kSourceColor{0.90f, 0.72f, 0.52f};
const Eigen::Vector3f kLoopColor{0.85f, 0.85f, 0.85f}, kPendingColor{1.0f, 0.92f, 0.25f};
const Eigen::Vector3f kSeamColor{1.0f, 0.85f, 0.1f}, kHandleColor{0.95f, 0.2f, 0.2f};
const Eigen::Vector3f kPaintColor{0.85f, 0.25f, 0.35f};
// Optimal-boundary mode: the rough region, the feature, the target region, and the boundaries.
const Eigen::Vector3f kRoughColor{0.98f, 0.86f, 0.55f}, kRegionColor{0.45f, 0.62f, 0.95f};
const Eigen::Vector3f kUserLoopColor{0.95f, 0.6f, 0.2f}, kOptimalLoopColor{0.3f, 0.9f, 0.35f};

Eigen::Vector3f pair_color(int pair) {
  static const Eigen::Vector3f palette[] = {
      {0.2f, 0.8f, 1.0f}, {0.3f, 1.0f, 0.45f}, {1.0f, 0.45f, 0.85f}, {0.65f, 0.55f, 1.0f}, {1.0f, 0.6f, 0.2f}};
  return palette[pair % 5];
}

std::vector<Eigen::Vector3d> loop_points(const geometry::TriMesh& m, const std::vector<int>& loop) {
  std::vector<Eigen::Vector3d> pts;
  for (int v : loop) pts.push_back(m.V.row(v).transpose());
  if (!loop.empty()) pts.push_back(m.V.row(loop.front()).transpose());  // closed
  return pts;
}

void add_point(viewer::PointItem& item, const Eigen::Vector3d& p, const Eigen::Vector3f& c) {
  const Eigen::Index n = item.points.rows();
  item.points.conservativeResize(n + 1, 3);
  item.colors.conservativeResize(n + 1, 3);
  item.points.row(n) = p.cast<float>().transpose();
  item.colors.row(n) = c.transpose();
}

}  // namespace

void MergeApp::update_scene(viewer::Viewer& v) {
  viewer::Scene& scene = v.scene();
  const bool result = show_result_ && shown_.has_value();
  update_inputs(scene, result);
  update_result(scene, result);
  update_loops(scene);
  update_markers(scene);
  update_optimal_loops(scene);
  scene_dirty_ = false;
}

void MergeApp::update_inputs(viewer::Scene& scene, bool result) {
  // The painted region, on whichever mesh it is.
  auto paint = [&](viewer::MeshItem& item, const Eigen::Vector3f& base, bool on_this) {
    item.colors.resize(0, 3);
    if (!on_this || painted_.empty()) return;
    item.colors = base.transpose().replicate(item.mesh.num_vertices(), 1);
    for (int p : painted_)
      if (p < item.mesh.num_vertices()) item.colors.row(p) = kPaintColor.transpose();
  };
  auto& target = scene.meshes["target"];
  target.mesh = target_.mesh;
  target.base_color = kTargetColor;
  paint(target, kTargetColor, !painted_on_source_);
  target.visible = !result;  // the result contains the target part
  ++target.version;

  auto& source = scene.meshes["source"];
  source.mesh = source_.mesh;
  source.base_color = kSourceColor;
  // Beside the result the source is a ghost where the user placed it, shown only where the
  // placement matters: dependent mode keeps it, and the move tool moves it.
  source.alpha = result ? 0.3f : 1.0f;
  source.visible = !result || setup().options.mode == mesh_merge::MergeMode::Dependent || tool_ == Tool::Move;
  paint(source, kSourceColor, painted_on_source_);
  if (optimal_mode()) paint_regions(source, target);
  // X-ray painting: the meshes translucent and the painted vertices drawn over them, hidden
  // ones too.
  const bool xray = xray_ && tool_ == Tool::Paint && !result;
  target.alpha = xray ? 0.45f : 1.0f;
  if (xray) source.alpha = 0.45f;
  ++source.version;
  auto& points = scene.points["x-ray painted"];
  const geometry::TriMesh& painted_mesh = painted_on_source_ ? source_.mesh : target_.mesh;
  points.visible = xray;
  points.points.resize(xray ? static_cast<Eigen::Index>(painted_.size()) : 0, 3);
  for (Eigen::Index k = 0; k < points.points.rows(); ++k)
    points.points.row(k) =
        painted_mesh.V.row(std::min(painted_[static_cast<size_t>(k)], painted_mesh.num_vertices() - 1)).cast<float>();
  points.base_color = kPaintColor;
  points.size = 3.0f;
  ++points.version;
}

// Optimal-boundary mode: the three regions, the one being painted as the stroke has it.
void MergeApp::paint_regions(viewer::MeshItem& source, viewer::MeshItem& target) const {
  auto tint = [](viewer::MeshItem& item, const Eigen::Vector3f& base, const std::vector<int>& vertices,
                 const Eigen::Vector3f& color) {
    if (item.colors.rows() != item.mesh.num_vertices())
      item.colors = base.transpose().replicate(item.mesh.num_vertices(), 1);
    for (int v : vertices)
      if (v < item.mesh.num_vertices()) item.colors.row(v) = color.transpose();
  };
  const mesh_merge::OptimalPicks& o = setup().optimal;
  auto shown = [&](int region, const std::vector<int>& picked) -> const std::vector<int>& {
    return painting_ && optimal_region_ == region ? painted_ : picked;
  };
  source.colors.resize(0, 3), target.colors.resize(0, 3);
  tint(source, kSourceColor, shown(0, o.rough), kRoughColor);
  tint(source, kSourceColor, shown(1, o.feature), kPaintColor);
  tint(target, kTargetColor, shown(2, o.target), kRegionColor);
  ++target.version;
}

// The rough region's border and the optimal boundary of the shown result, on the source.
void MergeApp::update_optimal_loops(viewer::Scene& scene) {
  auto& item = scene.lines["optimal boundary"];
  item.clear();
  item.visible = optimal_mode() && shown_ && shown_->boundary;
  item.on_top = true;
  item.width = 3.0f;
  if (!item.visible) return;
  const mesh_merge::OptimalBoundary& b = *shown_->boundary;
  item.add_strip(loop_points(source_.mesh, b.user_loop), kUserLoopColor);
  item.add_strip(loop_points(source_.mesh, b.loop), kOptimalLoopColor);
}

// The merged mesh, its source part tinted, and its seam strips outlined.
void MergeApp::update_result(viewer::Scene& scene, bool result) {
  auto& merged = scene.meshes["result"];
  merged.visible = result;
  if (result) {
    const mesh_merge::MergeResult& r = shown_->result;
    merged.mesh = r.mesh;
    merged.colors = kTargetColor.transpose().replicate(r.mesh.num_vertices(), 1);
    for (int m : r.source_map)
      if (m >= 0) merged.colors.row(m) = kSourceColor.transpose();
    // The transition band (§3.3.3) shaded by how much of each mesh its details come from.
    for (size_t k = 0; k < r.transition_vertices.size(); ++k) {
      const float tau = static_cast<float>(r.transition_share[k]);
      merged.colors.row(r.transition_vertices[k]) = (tau * kTargetColor + (1 - tau) * kSourceColor).transpose();
    }
  }
  ++merged.version;

  auto& seam = scene.lines["seam"];
  seam.clear();
  seam.visible = result;
  if (result) {
    const geometry::TriMesh& m = shown_->result.mesh;
    for (int f : shown_->result.strip_faces)
      seam.add_strip(
          std::vector<Eigen::Vector3d>{m.V.row(m.F(f, 0)), m.V.row(m.F(f, 1)), m.V.row(m.F(f, 2)), m.V.row(m.F(f, 0))},
          kSeamColor);
  }
  seam.width = 1.5f;
}

void MergeApp::update_loops(viewer::Scene& scene) {
  const bool source_visible = scene.meshes["source"].visible;
  // Loops on top of everything: they are what the user clicks. The source's go with the
  // source (hidden beside an independent result: Tab shows the inputs to pick on).
  for (int side = 0; side < 2; ++side) {
    const PickableMesh& pm = side == 0 ? source_ : target_;
    auto& item = scene.lines[side == 0 ? "loops source" : "loops target"];
    item.clear();
    item.visible = side == 1 || source_visible;
    item.on_top = true;
    item.width = 3.0f;
    for (size_t l = 0; l < pm.loops().size(); ++l) {
      const int loop = static_cast<int>(l);
      const int pair = side == 0 ? pair_of_source_loop(loop) : pair_of_target_loop(loop);
      const bool pending = loop == (side == 0 ? pending_source_loop_ : pending_target_loop_);
      item.add_strip(loop_points(pm.mesh, pm.loops()[l]), pending     ? kPendingColor
                                                          : pair >= 0 ? pair_color(pair)
                                                                      : kLoopColor);
    }
  }
}

// The key correspondences and the fixed handles.
void MergeApp::update_markers(viewer::Scene& scene) {
  const bool source_visible = scene.meshes["source"].visible;
  auto& keys = scene.points["keys"];
  keys.points.resize(0, 3);
  keys.colors.resize(0, 3);
  keys.size = 11.0f;
  for (size_t p = 0; p < setup().pairs.size(); ++p)
    for (const auto& k : setup().pairs[p].keys) {
      if (source_visible) add_point(keys, source_.mesh.V.row(k.source).transpose(), pair_color(static_cast<int>(p)));
      add_point(keys, target_.mesh.V.row(k.target).transpose(), pair_color(static_cast<int>(p)));
    }
  if (pending_key_source_ >= 0) add_point(keys, source_.mesh.V.row(pending_key_source_).transpose(), kPendingColor);
  if (pending_key_target_ >= 0) add_point(keys, target_.mesh.V.row(pending_key_target_).transpose(), kPendingColor);
  ++keys.version;

  auto& handles = scene.points["handles"];
  handles.points.resize(0, 3);
  handles.colors.resize(0, 3);
  handles.size = 7.0f;
  handles.on_top = false;
  for (int h : setup().options.handles)
    if (h >= 0 && h < source_.mesh.num_vertices()) add_point(handles, source_.mesh.V.row(h).transpose(), kHandleColor);
  handles.visible = setup().options.mode == mesh_merge::MergeMode::Dependent;
  ++handles.version;
}

// The gizmo sits at the placed source's centroid and keeps its size on screen, so it is
// redrawn every frame (the camera may have moved).
void MergeApp::update_gizmo(viewer::Viewer& v) {
  auto& item = v.scene().lines["gizmo"];
  item.visible = tool_ == Tool::Move && source_.mesh.num_vertices() > 0;
  if (!item.visible) return;
  gizmo_.set_center(source_.mesh.V.colwise().mean().transpose());
  gizmo_.draw(v.camera_matrices(), item);
  ++item.version;
}

// Numbered markers: "1", "2", ... per pair (prefixed with the pair's number when there are
// several), beside both ends of every key correspondence.
void MergeApp::draw_labels(viewer::Viewer& v) {
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  const auto cam = v.camera_matrices();
  const bool several = setup().pairs.size() > 1;
  const bool source_shown = v.scene().meshes["source"].visible;
  for (size_t p = 0; p < setup().pairs.size(); ++p) {
    const Eigen::Vector3f c = pair_color(static_cast<int>(p));
    const ImU32 color = ImGui::ColorConvertFloat4ToU32(ImVec4(c.x(), c.y(), c.z(), 1.0f));
    const auto& keys = setup().pairs[p].keys;
    for (size_t k = 0; k < keys.size(); ++k) {
      const std::string label = several ? std::to_string(p + 1) + "." + std::to_string(k + 1) : std::to_string(k + 1);
      for (int side = source_shown ? 0 : 1; side < 2; ++side) {
        const Eigen::Vector3d w = side == 0 ? Eigen::Vector3d(source_.mesh.V.row(keys[k].source))
                                            : Eigen::Vector3d(target_.mesh.V.row(keys[k].target));
        const Eigen::Vector3d s = geometry::project(cam, w);
        if (s.z() <= 0 || s.z() >= 1) continue;
        const ImVec2 at(static_cast<float>(s.x()) + 8, static_cast<float>(s.y()) - 18);
        draw->AddText(ImVec2(at.x + 1, at.y + 1), IM_COL32(0, 0, 0, 255), label.c_str());
        draw->AddText(at, color, label.c_str());
      }
    }
  }
}

}  // namespace lapis::merge_app
