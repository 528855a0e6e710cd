// lapis-merge's drag tools, on the viewer's shared widgets: the gizmo moves the source (what
// configuration-dependent merging keeps), the brush paints a region on either mesh that
// mesh_merge::cut_by_region() cuts off (the painted part of the source, the rest of the target),
// so a closed mesh can give a part with an open rim. With x-ray on the brush paints through the
// surface, so a stroke across an arm takes its back too and the cut goes all round it.
#include <algorithm>
#include <iterator>

#include "lapis/mesh_merge/cut.h"
#include "lapis/viewer/picking.h"
#include "merge_app.h"

namespace lapis::merge_app {

// ---------------------------------------------------------------- move (gizmo)

void MergeApp::press_move(viewer::Viewer& v, double x, double y) {
  if (!gizmo_.begin_drag(v.camera_matrices(), {x, y})) return v.flash("grab an arrow, a ring or the centre square");
  drag_start_ = setup().placement;
}

void MergeApp::drag_move(viewer::Viewer& v, double x, double y) {
  // Preview only: the placed source follows the drag; the setup changes once, on release.
  const Eigen::Matrix4d T = gizmo_.drag_to({x, y}) * *drag_start_;
  MergeSetup preview = setup();
  preview.placement = T;
  auto& item = v.scene().meshes["source"];
  item.mesh = mesh_merge::placed_source(preview);
  ++item.version;
}

void MergeApp::release_move(viewer::Viewer& v) {
  MergeSetup next = setup();
  next.placement = gizmo_.drag_to(v.cursor()) * *drag_start_;
  gizmo_.end_drag();
  drag_start_.reset();
  if (next.placement != setup().placement) commit(v, std::move(next), "move source");
}

// ---------------------------------------------------------------- paint and cut

void MergeApp::press_paint(viewer::Viewer& v, double x, double y, bool erase) {
  painting_ = true;
  erasing_ = erase;
  paint_mesh_chosen_ = false;                 // by the first surface the stroke touches (it may start beside it)
  if (optimal_mode()) begin_region_stroke();  // the chosen region, on its mesh
  drag_paint(v, x, y);
}

void MergeApp::drag_paint(viewer::Viewer& v, double x, double y) {
  const auto cam = v.camera_matrices();
  if (!paint_mesh_chosen_) {
    const auto s = viewer::pick(*source_.bvh, cam, x, y), t = viewer::pick(*target_.bvh, cam, x, y);
    if (!s && !t) return;
    const bool on_source = s && (!t || s->t <= t->t);
    if (on_source != painted_on_source_) painted_.clear();  // one mesh at a time
    painted_on_source_ = on_source;
    paint_mesh_chosen_ = true;
  }
  const PickableMesh& m = painted_on_source_ ? source_ : target_;
  viewer::BrushOptions brush;
  brush.radius_px = brush_px_;
  brush.through = xray_;
  const std::vector<int> under = viewer::brush_vertices(m.mesh, *m.conn, *m.bvh, cam, {x, y}, brush);
  if (under.empty()) return;
  std::vector<int> next;
  if (erasing_)
    std::set_difference(painted_.begin(), painted_.end(), under.begin(), under.end(), std::back_inserter(next));
  else
    std::set_union(painted_.begin(), painted_.end(), under.begin(), under.end(), std::back_inserter(next));
  painted_ = std::move(next);
  scene_dirty_ = true;
}

void MergeApp::add_painted_feature(viewer::Viewer& v) {
  if (!painted_on_source_ || painted_.size() < 4)  // a shared gradient needs 4 vertices
    return v.flash("paint a fixed feature on the source first (tool 5, at least 4 vertices)");
  MergeSetup next = setup();
  next.options.features.push_back(painted_);
  painted_.clear();
  commit(v, std::move(next), "add feature");
}

void MergeApp::cut_painted(viewer::Viewer& v) {
  if (optimal_mode()) return v.flash("the optimal-boundary mode paints regions; it cuts along the boundary it finds");
  if (painted_.empty()) return v.flash("paint a region first (tool 5: left-drag paints, Shift erases)");
  const bool on_source = painted_on_source_;
  try {
    if (on_source) {
      // The source keeps the painted part (the head taken off a bust), where it was placed.
      mesh_merge::RegionCut cut = mesh_merge::cut_by_region(*setup().source, painted_);
      auto part = std::make_shared<const geometry::TriMesh>(std::move(cut.inside));
      replace_meshes(v, part, source_name() + " (cut)", setup().target, target_name(), "cut source", Placement::Keep);
    } else {
      // The target keeps the rest (the body the head is taken off).
      mesh_merge::RegionCut cut = mesh_merge::cut_by_region(*setup().target, painted_);
      auto rest = std::make_shared<const geometry::TriMesh>(std::move(cut.outside));
      replace_meshes(v, setup().source, source_name(), rest, target_name() + " (cut)", "cut target", Placement::Keep);
    }
    tool_ = Tool::PairLoops;  // the new rim is ready to pair
    const geometry::TriMesh& kept = on_source ? *setup().source : *setup().target;
    const geometry::Connectivity conn(kept);
    v.flash(std::string("cut: the ") + (on_source ? "source" : "target") + " keeps " +
            std::to_string(kept.num_vertices()) + " vertices, " + std::to_string(conn.boundary_loops().size()) +
            " boundary loop(s)");
  } catch (const Error& e) {
    v.flash(e.what(), viewer::Tone::Error);
  }
}

}  // namespace lapis::merge_app
