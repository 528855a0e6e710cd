// lapis-merge: merge two meshes by picking their boundary loops (Poisson mesh merging, thesis
// §3.3). The app wires the viewer's input and panels to mesh_merge: the user's picks edit a
// mesh_merge::MergeSetup kept in an undo history, a Merger (precomputed once per source and
// options) re-merges on a worker thread, and the newest finished result is drawn.
#pragma once

#include <atomic>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "first_view.h"
#include "lapis/geometry/bvh.h"
#include "lapis/geometry/connectivity.h"
#include "lapis/mesh_merge/merge_setup.h"
#include "lapis/mesh_merge/metrics.h"
#include "lapis/mesh_merge/optimal_boundary.h"
#include "lapis/viewer/gizmo.h"
#include "lapis/viewer/latest_worker.h"
#include "lapis/viewer/loop_picking.h"
#include "lapis/viewer/surface_select.h"
#include "lapis/viewer/undo_history.h"
#include "lapis/viewer/viewer.h"

namespace lapis::merge_app {

using mesh_merge::MergeSetup;

// Auto-merge runs after every change while the last merge took less than this.
constexpr double kAutoMergeMs = 500.0;

enum class Tool { PairLoops, Keys, Handles, Move, Paint };
const char* tool_name(Tool t);

// The band widths a first switch to transition mode (§3.3.3) starts from: the module's
// suggestion for the paired target loops, or a twentieth of the target's size before any pair
// has a key.
double first_band_width(const mesh_merge::MergeSetup& s);

// "rough region (source)", "feature (source)" or "target region": the regions of the optimal
// mode, in the order of MergeApp's region choice.
const char* optimal_region_name(int region);

// The undoable state: the setup and a revision number that stays with it through undo and
// redo, so a merge result can be matched to the setup it was computed for.
struct Snapshot {
  MergeSetup setup;
  std::string source_name, target_name;  // as the panel shows them (they change with the meshes)
  std::uint64_t revision = 0;
};

// A mesh as the app shows and picks it: positions, adjacency, boundary loops and a BVH, rebuilt
// only when the mesh (or the source's placement) changes.
struct PickableMesh {
  std::shared_ptr<const geometry::TriMesh> rest;  // what it was built from
  Eigen::Matrix4d placement = Eigen::Matrix4d::Identity();
  geometry::TriMesh mesh;  // placed
  std::unique_ptr<geometry::Connectivity> conn;
  std::unique_ptr<geometry::Bvh> bvh;
  const std::vector<std::vector<int>>& loops() const { return conn->boundary_loops(); }
};

// What the worker hands back for one setup revision.
struct MergeOutcome {
  std::uint64_t revision = 0;
  std::shared_ptr<const geometry::TriMesh> source, target;  // the meshes it merged
  std::string error;                                        // a lapis::Error's message; the rest is empty then
  mesh_merge::MergeResult result;
  mesh_merge::SeamQuality quality;
  mesh_merge::DetailPreservation detail;
  double precompute_ms = 0;                             // of the Merger used (built for this job or reused)
  bool reused = false;                                  // the Merger was kept from an earlier job
  double job_ms = 0;                                    // precompute + merge + metrics, what the user waits
  std::optional<mesh_merge::OptimalBoundary> boundary;  // OptimalBoundary mode: the boundary merged along
  double feature_distortion = 0;                        // OptimalBoundary mode: Ωf's, metrics.h
};

// What a merge of the same setup with one more edit would cost: the job without the Merger's
// one-off precompute when it built one (the next edit of pairs, keys or smoothing reuses it).
// Auto-merge judges by this, not by the first merge of a setup, which pays the precompute.
inline double remerge_ms(const MergeOutcome& o) { return o.reused ? o.job_ms : o.job_ms - o.precompute_ms; }

// The optimal-boundary search's progress, written by the worker, read by the overlay.
struct OptimalProgress {
  std::atomic<int> iteration{0};  // iterations done in the running search (0: none yet)
  std::atomic<double> energy{0};  // its last E(B_k, T_k)
};

struct AppPaths {
  std::filesystem::path export_prefix = "out/merge";  // <prefix>.obj, <prefix>_pairs.json, ...
  bool export_on_exit = false;                        // batch runs
  std::filesystem::path asset_dir;                    // holds merge/ and external/ (bundled meshes)
};

class MergeApp final : public viewer::ViewerApp {
 public:
  MergeApp(MergeSetup setup, std::string source_name, std::string target_name, AppPaths paths);
  ~MergeApp() override;

  void on_start(viewer::Viewer& v) override;
  bool on_event(viewer::Viewer& v, const viewer::InputEvent& e) override;
  void on_frame(viewer::Viewer& v) override;
  void on_gui(viewer::Viewer& v) override;
  void on_exit(viewer::Viewer& v) override;
  int exit_status() const override { return exit_status_; }
  bool busy() const override;
  void benchmark_fields(nlohmann::json& j) const override;

 private:
  const MergeSetup& setup() const { return history_.current().setup; }
  std::uint64_t revision() const { return history_.current().revision; }
  const std::string& source_name() const { return history_.current().source_name; }
  const std::string& target_name() const { return history_.current().target_name; }
  void commit(viewer::Viewer& v, MergeSetup next, std::string name);
  void undo(viewer::Viewer& v);
  void redo(viewer::Viewer& v);
  void after_history_step();
  void clear_picks();

  // Input (merge_app.cpp).
  bool handle_key(viewer::Viewer& v, const viewer::InputEvent& e);
  void click(viewer::Viewer& v, double x, double y);
  void click_pair_loops(viewer::Viewer& v, double x, double y);
  void show_inputs_to_pick(viewer::Viewer& v);
  // K: every pair's key suggested as the source is placed (mesh_merge::suggest_keys).
  void suggest_all_keys(viewer::Viewer& v);
  // What is wrong with the shown result that its numbers alone hide: the source turned over
  // (more than 90° from its placement: face-down) or folded seam edges; "" when neither.
  std::string result_flag() const;
  void flash_suggestion(viewer::Viewer& v, int pair, const mesh_merge::KeySuggestion& s);
  void click_keys(viewer::Viewer& v, double x, double y);
  void click_handles(viewer::Viewer& v, double x, double y);
  void press_move(viewer::Viewer& v, double x, double y);
  void drag_move(viewer::Viewer& v, double x, double y);
  void release_move(viewer::Viewer& v);
  void press_paint(viewer::Viewer& v, double x, double y, bool erase);
  void drag_paint(viewer::Viewer& v, double x, double y);
  void cut_painted(viewer::Viewer& v);
  void add_painted_feature(viewer::Viewer& v);  // §3.5: the region painted on the source, as a fixed feature
  int pair_of_source_loop(int loop) const;
  int pair_of_target_loop(int loop) const;

  // Meshes. Where the source goes when the meshes change: as before (a cut), at its own
  // coordinates (the bundled presets, authored so), or beside the target at its size (an opened
  // mesh, mesh_merge::suggest_placement()).
  enum class Placement { Keep, Identity, Suggested };
  void frame(viewer::Viewer& v);
  void replace_meshes(viewer::Viewer& v, std::shared_ptr<const geometry::TriMesh> source, std::string source_name,
                      std::shared_ptr<const geometry::TriMesh> target, std::string target_name, std::string edit,
                      Placement placement = Placement::Identity);
  void load_mesh(viewer::Viewer& v, const std::filesystem::path& path, bool as_source);
  void load_preset(viewer::Viewer& v, int preset);
  void refresh_pickables();

  // Engine.
  void request_merge();
  void receive_merge(viewer::Viewer& v);
  bool auto_merge_allowed() const;

  // Exports (merge_export.cpp).
  // Writes the merge and the files that reproduce it; false when nothing was written.
  bool export_all(viewer::Viewer& v);

  // Optimal-boundary mode (merge_optimal.cpp).
  bool optimal_mode() const;
  static std::vector<int>& region_of(MergeSetup& s, int region);
  void begin_region_stroke();
  void end_region_stroke(viewer::Viewer& v);
  std::shared_ptr<const mesh_merge::BoundaryOptimizer> optimizer();
  mesh_merge::Placement2D current_placement();
  std::string edit_optimal(MergeSetup& next);
  void draw_placement_window(viewer::Viewer& v);
  static void run_optimal(MergeOutcome& out, const MergeSetup& s,
                          const std::shared_ptr<const mesh_merge::BoundaryOptimizer>& opt, const std::string& error,
                          const mesh_merge::Placement2D& placement, const std::shared_ptr<OptimalProgress>& progress);
  void update_optimal_loops(viewer::Scene& scene);
  void paint_regions(viewer::MeshItem& source, viewer::MeshItem& target) const;

  // Drawing (merge_scene.cpp) and panels (merge_panels.cpp).
  void update_scene(viewer::Viewer& v);
  void update_inputs(viewer::Scene& scene, bool result);  // result: the merged mesh is shown
  void update_result(viewer::Scene& scene, bool result);
  void update_loops(viewer::Scene& scene);
  void update_markers(viewer::Scene& scene);
  void update_gizmo(viewer::Viewer& v);
  void draw_labels(viewer::Viewer& v);
  void draw_menu(viewer::Viewer& v);
  void draw_merge_panel(viewer::Viewer& v);
  void draw_inputs_and_tools(viewer::Viewer& v);
  std::string edit_pairs(MergeSetup& next);  // each edit_* returns the name of its edit, or ""
  std::string edit_mode(MergeSetup& next);
  std::string edit_mode_options(MergeSetup& next);
  std::string edit_transition_bands(mesh_merge::TransitionOptions& t);
  void draw_merge_actions(viewer::Viewer& v);
  void draw_result_panel(viewer::Viewer& v);
  void draw_overlay(viewer::Viewer& v);
  void draw_paint_controls(viewer::Viewer& v);

  viewer::UndoHistory<Snapshot> history_;
  std::uint64_t last_revision_ = 1;
  AppPaths paths_;
  PickableMesh source_, target_;

  Tool tool_ = Tool::PairLoops;
  int pending_source_loop_ = -1, pending_target_loop_ = -1;  // half-made loop pair
  int pending_key_source_ = -1, pending_key_target_ = -1;    // half-made key (vertex)
  // Move tool: the gizmo on the source; the placement being dragged (committed on release).
  viewer::Gizmo gizmo_;
  std::optional<Eigen::Matrix4d> drag_start_;
  // Paint tool: a vertex set painted on one of the meshes, cut off by cut_painted().
  std::vector<int> painted_;
  bool painted_on_source_ = true;
  bool painting_ = false, erasing_ = false, paint_mesh_chosen_ = false;
  float brush_px_ = 24;
  bool xray_ = false;  // the brush paints through the surface (X): a cut goes all round an arm

  // Optimal-boundary mode: the region the brush paints (0 rough, 1 feature, 2 target), the
  // optimizer of the current regions (its set-up is the fill and both conformal maps), the
  // placement being dragged in the 2D view, and the running search's progress.
  int optimal_region_ = 1;
  struct OptimizerCache {
    std::shared_ptr<const geometry::TriMesh> source, target;
    Eigen::Matrix4d placement = Eigen::Matrix4d::Identity();
    std::vector<int> rough, feature, region;
    std::shared_ptr<const mesh_merge::BoundaryOptimizer> optimizer;
    mesh_merge::Placement2D suggested;
    std::string error;
  };
  OptimizerCache optimizer_;
  std::optional<mesh_merge::Placement2D> placement_drag_;
  std::shared_ptr<OptimalProgress> optimal_progress_ = std::make_shared<OptimalProgress>();

  float merge_panel_bottom_ = 0;  // where the result panel goes
  bool show_result_ = true;       // result (with translucent inputs) or the inputs alone
  bool auto_merge_ = true;
  bool scene_dirty_ = true;
  bool export_pending_ = false;
  int exit_status_ = 0;  // 1 when the export on exit wrote nothing

  // Engine: a Merger is kept between jobs while the source and the options it was built
  // with stay the same (only the worker touches it).
  struct EngineSlot {
    std::unique_ptr<mesh_merge::Merger> merger;
    std::shared_ptr<const geometry::TriMesh> source;
    Eigen::Matrix4d placement;
    mesh_merge::MergeOptions options;
  };
  std::shared_ptr<EngineSlot> engine_ = std::make_shared<EngineSlot>();
  std::uint64_t requested_revision_ = 0;            // 0: none
  std::optional<MergeOutcome> last_;                // newest finished job (may be an error)
  std::optional<MergeOutcome> shown_;               // newest successful one, on screen
  std::vector<double> job_ms_, frame_at_merge_ms_;  // for --benchmark
  std::optional<double> remerge_ms_;                // of the newest finished job: auto-merge's measure
  viewer::LatestWorker<MergeOutcome> worker_;       // last: joined first, before what jobs use
};

}  // namespace lapis::merge_app
