// lapis-deform: paint a region of interest, a fixed region and handles on a mesh, drag a
// handle with the gizmo and watch the mesh follow (thesis ch. 2 and its baselines). The app
// wires the viewer's input and panels to the mesh_deform module: painted labels become a
// Selection (vertex_labels.h), a LiveDeformer on a worker thread sets up once per selection
// and solves each frame, and the newest finished frame is drawn when it is ready.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lapis/geometry/bvh.h"
#include "lapis/geometry/connectivity.h"
#include "lapis/mesh_deform/deformation_transfer.h"
#include "lapis/mesh_deform/feature_labels.h"
#include "lapis/mesh_deform/live_deformer.h"
#include "lapis/mesh_deform/vertex_labels.h"
#include "lapis/viewer/gizmo.h"
#include "lapis/viewer/latest_worker.h"
#include "lapis/viewer/panel_column.h"
#include "lapis/viewer/undo_history.h"
#include "lapis/viewer/viewer.h"
#include "transfer_pairing.h"

namespace lapis::deform_app {

// The width of the panels down the window's right edge.
constexpr float kPanelWidth = 340;

using namespace lapis::mesh_deform;
namespace fs = std::filesystem;

// Connected: a click takes the clicked vertex's connected region; Geodesic: the vertices
// within a geodesic radius of it; Pair: place the transfer target's handles.
enum class Tool { Move, Brush, Lasso, Connected, Geodesic, Pair };
const char* tool_name(Tool t);

enum class ColorMode { Selection, Distortion, Saliency, IsolineField, Rigidity };

// Colour of region handle `label` on the surface and in the panels.
Eigen::Vector3f handle_color(int label);
// Colour of the fixed region (outside the ROI).
Eigen::Vector3f fixed_color();
// Colour of salient feature `index` (the salient method's rigid parts).
Eigen::Vector3f feature_color(int index);

// The paint target that paints the active salient feature (beside VertexLabels' kRoi, kFixed,
// kNone and the handle indices).
inline constexpr int kFeatureTarget = -10;

struct DeformPaths {
  fs::path mesh;                // the mesh opened (the CLI's --mesh for the export)
  fs::path roi, handles;        // selection files: Ctrl+S saves, Ctrl+O opens
  fs::path export_mesh;         // Ctrl+E; beside it <stem>.roi.txt, .handles.json, .deform.json
  fs::path screenshot;          // Ctrl+P and the File panel's button
  bool export_on_exit = false;  // batch runs: export when the app closes
  fs::path bundled_dir;         // meshes the file panel offers (assets/external)
};

// The files of `mesh` (the selection, the export, the screenshot), named after it: next to
// it, or in out/ of the working directory for a bundled mesh and where its directory is not
// writable (an installed share/lapis). Each mesh has its own, so opening a second one never
// overwrites the first one's selection. `variant` tells apart versions of one file with other
// vertices (".sub2": Loop-subdivided twice). Keeps `defaults`' other fields.
DeformPaths paths_beside(const fs::path& mesh, DeformPaths defaults, const std::string& variant = "");

// The undoable state: painted labels (shared between snapshots that did not repaint) and
// one transform per handle label.
struct EditState {
  std::shared_ptr<const VertexLabels> labels;
  std::vector<Eigen::Matrix4d> transforms;  // by handle label; identity = rest pose
  int active_handle = 0;
};

// What the worker hands back for one request.
struct Solved {
  std::uint64_t request = 0, epoch = 0, revision = 0;  // request id, mesh epoch, selection revision
  std::shared_ptr<const Selection> selection;
  MethodSettings settings;
  LiveFrame frame;
  std::optional<DistortionField> field;  // what frame.distortion measures
  bool recolor = false;                  // the previous frame with another distortion field, not a solve
};

// ARAP after an edit: rounds of ArapOptions' iterations on the same pose until a round lowers
// the energy by less than this fraction, or kArapMaxRounds.
inline constexpr double kArapRoundTolerance = 1e-4;
inline constexpr int kArapMaxRounds = 100;

// What the transfer worker hands back: the target deformed like one source frame.
struct Transferred {
  std::uint64_t request = 0, epoch = 0;  // request id, target epoch
  std::uint64_t source_request = 0;      // the source frame it carries (Solved::request)
  std::uint64_t pairing_revision = 0;    // the target handles it was set up with
  geometry::Vertices positions;          // in the target's own frame
  TransferReport report;
  double ms = 0;
};

class DeformApp final : public viewer::ViewerApp {
 public:
  DeformApp(geometry::TriMesh mesh, DeformPaths paths, MethodSettings settings, bool preview_while_dragging = true);
  ~DeformApp() override;

  void on_start(viewer::Viewer& v) override;
  bool on_event(viewer::Viewer& v, const viewer::InputEvent& e) override;
  void on_frame(viewer::Viewer& v) override;
  void on_gui(viewer::Viewer& v) override;
  void on_exit(viewer::Viewer& v) override;
  int exit_status() const override { return exit_status_; }
  bool may_close(viewer::Viewer& v) override;  // asks first when there are unsaved edits
  bool asking() const override { return leave_prompt_.has_value(); }
  bool busy() const override;
  void benchmark_fields(nlohmann::json& j) const override;

  // Opens the ROI and handles files of the paths when the app starts.
  void open_selection_on_start() { load_on_start_ = true; }
  // Opens a deformation-transfer target beside the mesh when the app starts.
  void open_transfer_target_on_start(fs::path path) { transfer_target_on_start_ = std::move(path); }
  // Colours by distortion on the fixed range [0, max] instead of each frame's 95th percentile.
  void fix_distortion_range(double max) {
    color_mode_ = ColorMode::Distortion;
    legend_fixed_ = true;
    legend_max_ = static_cast<float>(max);
    legend_hi_ = max;
  }

 private:
  // Loads the ROI and handles files (CLI formats); errors are shown, not thrown.
  void load_selection(viewer::Viewer& v);
  // Input (deform_input.cpp).
  bool handle_key(viewer::Viewer& v, const viewer::InputEvent& e);
  bool handle_command_key(viewer::Viewer& v, int key, bool shift);
  bool handle_tool_key(int key);
  bool handle_edit_key(viewer::Viewer& v, int key);
  void select_next_painted_handle();
  bool press(viewer::Viewer& v, const Eigen::Vector2d& p, int mods);
  void move(viewer::Viewer& v, const Eigen::Vector2d& p);
  void release(viewer::Viewer& v);
  void paint_at(viewer::Viewer& v, const Eigen::Vector2d& p);
  int paint_value() const;   // the label the current target paints (kNone while erasing)
  int target_value() const;  // the label the current target stands for: kRoi, kFixed, kNone or the active handle
  void ensure_pick_structures();

  // Edits (deform_app.cpp).
  void commit(std::string label);  // pushes state_ onto the undo history
  void set_labels(std::shared_ptr<const VertexLabels> labels, const std::string& label);
  void labels_changed();  // rebuilds the selection from the labels
  void undo(viewer::Viewer& v);
  void redo(viewer::Viewer& v);
  void step_history(viewer::Viewer& v, bool forward);
  void reset_pose(viewer::Viewer& v);
  void grow_or_shrink(viewer::Viewer& v, int rings);
  void clear_target(viewer::Viewer& v);
  // Paints (or, erasing, clears) `vertices` with the current target as one undoable edit; the
  // feature target paints the active feature.
  void paint_set(viewer::Viewer& v, const std::vector<int>& vertices, const std::string& label);
  void commit_features(std::vector<int> feature_of);

  // Click selections and symmetry (deform_select.cpp).
  bool select_at(viewer::Viewer& v, const Eigen::Vector2d& p, bool erase);  // Tool::Connected, Tool::Geodesic
  void mirror_target(viewer::Viewer& v);  // adds the mirror image of what acts as the target
  int mirror_axis();                      // the panel's plane, or the most symmetric one (auto)
  double diagonal() const;                // of the rest mesh's bounding box
  void update_roi_warning();              // handles the ROI's border passes close to
  void draw_roi_warning(viewer::Viewer& v);
  void draw_roi_warning_details() const;  // in the Selection panel
  void new_handle();
  Eigen::Matrix4d& active_transform();
  Eigen::Vector3d handle_rest_centroid(int label) const;

  // Files.
  void open_mesh(viewer::Viewer& v, const fs::path& path);
  void save_selection(viewer::Viewer& v);
  // Writes the result and the files that reproduce it; false when nothing was written.
  bool export_result(viewer::Viewer& v);
  bool export_ready() const;

  // Engine.
  void request_solve();
  void request_recolor();  // the newest frame's distortion for another colour mode, no solve
  void continue_arap();    // another round on the same pose while the energy still falls
  void receive(viewer::Viewer& v);

  // Deformation transfer (deform_transfer.cpp): a target beside the mesh, its handles placed
  // by clicking (Tool::Pair), the newest frame carried onto it on a second worker.
  void open_transfer_target(viewer::Viewer& v, const fs::path& path);
  void close_transfer_target(viewer::Viewer& v);
  bool pair_at(viewer::Viewer& v, const Eigen::Vector2d& p);
  void transfer_source_changed();  // the painted selection changed: the pairs follow
  void request_transfer();
  void receive_transfer(viewer::Viewer& v);
  bool transfer_ready() const;  // nothing to transfer, or the newest frame transferred
  // Writes the target deformed and the files `lapis transfer` reproduces it from (in the
  // export's file group); adds their names and the command to `j`. False: nothing written.
  bool export_transfer(const fs::path& stem, const fs::path& source_out, nlohmann::json& j);
  void draw_transfer_panel(viewer::Viewer& v);

  // Drawing (deform_scene.cpp) and panels (deform_panels.cpp).
  void update_surface(viewer::Viewer& v);
  void update_gizmo(viewer::Viewer& v);
  bool gizmo_shown() const;  // a valid selection and a painted active handle
  void update_markers(viewer::Viewer& v);
  void update_target_surface(viewer::Viewer& v);
  void draw_tools_panel(viewer::Viewer& v, viewer::PanelColumn& column);
  void draw_method_panel(viewer::PanelColumn& column);
  void draw_handle_panel(viewer::PanelColumn& column);
  void draw_file_panel(viewer::Viewer& v);
  void draw_legend(viewer::Viewer& v);
  void draw_feature_controls();
  void features_received(const LiveFrame& f);
  void draw_overlay(viewer::Viewer& v);
  void draw_cursor(viewer::Viewer& v);
  // Files (deform_files.cpp): the File panel's fields follow paths_; the edits since the
  // selection was last saved, opened or exported; the prompt before they would be lost (quit,
  // another mesh).
  void fill_file_fields();
  void mark_saved() { saved_state_ = state_; }
  bool unsaved() const;
  void open_mesh_or_ask(viewer::Viewer& v, const fs::path& path);
  void draw_leave_prompt(viewer::Viewer& v);
  enum class LeaveChoice { Stay, Save, Discard };
  void leave(viewer::Viewer& v, LeaveChoice choice);  // answers the prompt

  geometry::TriMesh rest_;
  std::unique_ptr<geometry::Connectivity> conn_;
  DeformPaths paths_;
  std::array<char, 1024> roi_field_{}, handles_field_{}, export_field_{};
  EditState saved_state_;
  std::optional<fs::path> leave_prompt_;  // asking about unsaved edits before quitting (an
                                          // empty path) or opening this mesh
  MethodSettings settings_;
  bool preview_while_dragging_ = true;  // implicit: first system while dragging (§2.5)
  bool load_on_start_ = false;

  // Editing.
  EditState state_;
  viewer::UndoHistory<EditState> history_;
  std::optional<LabelledSelection> selection_;
  std::string selection_error_;
  std::uint64_t selection_revision_ = 0;
  std::shared_ptr<VertexLabels> stroke_;  // labels being painted (committed on release)
  std::vector<Eigen::Vector2d> lasso_;
  Eigen::Vector2d last_paint_ = Eigen::Vector2d::Zero();
  Tool tool_ = Tool::Move;
  int target_ = VertexLabels::kRoi;  // kRoi, kFixed, kNone (erase) or 0 = the active handle
  bool erase_ = false;               // Shift held at press: this stroke erases
  float brush_px_ = 24;
  bool xray_ = false;                    // brush and lasso select through the surface (X)
  bool connected_within_label_ = false;  // Tool::Connected stops where the clicked vertex's label ends
  float geodesic_radius_ = 0.04f;        // Tool::Geodesic, of the bounding box's diagonal
  int mirror_choice_ = 0;                // 0 auto, 1 x, 2 y, 3 z: the plane through the bounding box's centre
  int auto_mirror_axis_ = -1;            // the auto plane, once measured
  float mirror_tolerance_ = 0.01f;       // a mirrored vertex's match, of the diagonal
  // The ROI warning: handle vertices within kWarnRings of the fixed region, and what it says.
  static constexpr int kWarnRings = 2;
  std::vector<int> warned_vertices_;
  std::string roi_warning_;
  FeatureLabels features_;        // the salient method's features as painted
  bool features_edited_ = false;  // the user changed them: they replace the detection
  std::uint64_t features_revision_ = 0;
  std::optional<std::vector<int>> feature_stroke_;  // feature_of being painted (committed on release)
  int active_feature_ = 0, merge_from_ = 1;
  viewer::Gizmo gizmo_;
  Eigen::Matrix4d drag_start_ = Eigen::Matrix4d::Identity();
  bool dragging_ = false;

  // Display.
  geometry::TriMesh shown_;  // the surface on screen: rest faces, rest or newest solved positions
  std::unique_ptr<geometry::Bvh> pick_bvh_;
  bool pick_stale_ = true, surface_dirty_ = true, markers_dirty_ = true;
  ColorMode color_mode_ = ColorMode::Selection;
  DistortionField field_ = DistortionField::EdgeLength;
  bool show_degenerate_ = true;
  double legend_hi_ = 0;  // the distortion colours' range [0, legend_hi_]
  // A range the user fixed (panel, --distortion-range), so frames and methods compare; otherwise
  // each solved frame's 95th percentile.
  bool legend_fixed_ = false;
  float legend_max_ = 0;
  void update_legend(const Eigen::VectorXd& distortion);
  // The isolines method's view of its last setup: a handle field, ψ and the isolines (rest mesh).
  Eigen::VectorXd isoline_field_, rigidity_;
  std::vector<mesh_deform::IsolineSegment> isolines_;

  // Engine: solves never block input; the previous result stays until a newer one arrives.
  // One per opened mesh, with its own copy of the mesh: a job still running on an old slot
  // never reads the app's current mesh.
  struct EngineSlot {
    explicit EngineSlot(const geometry::TriMesh& mesh) : live(mesh) {}
    LiveDeformer live;
  };
  std::shared_ptr<EngineSlot> engine_;
  std::uint64_t epoch_ = 0;      // bumped when a new mesh is opened
  std::uint64_t submitted_ = 0;  // id of the newest request
  std::uint64_t received_ = 0;   // id of the newest result taken (or failed)
  std::string last_key_;         // what the newest request asked for, to skip repeats
  std::string solve_key_;        // the same without the ARAP round: an edit when it changes
  int arap_round_ = 0;           // rounds run on the current pose after the first solve
  double arap_energy_ = -1;      // the energy the last round ended with
  std::string convergence_;      // what the rounds did, for the overlay
  double preview_gap_ = -1;      // implicit: how far the release moved the last preview shown (of the diagonal)
  std::optional<Solved> last_;
  std::string engine_error_;
  double setup_started_ = -1;  // time a request needing setup was submitted
  bool pending_export_ = false;
  int exit_status_ = 0;                      // 1 when the export on exit wrote nothing
  std::vector<double> solve_ms_, setup_ms_;  // for --benchmark
  long drag_frames_ = 0;
  double now_ = 0;
  long frame_ = 0, result_frame_ = -10;  // a new result settles (panels resize) before it counts as shown

  // Deformation transfer: the target as paired, and its engine (its own copies of both meshes).
  struct TransferSlot {
    TransferSlot(geometry::TriMesh s, geometry::TriMesh t) : source(std::move(s)), target(std::move(t)) {}
    geometry::TriMesh source, target;
    std::unique_ptr<DeformationTransfer> transfer;
    std::uint64_t pairing_revision = 0;  // what `transfer` was set up for
  };
  std::optional<TransferPairing> pairing_;
  fs::path target_path_, transfer_target_on_start_;
  Placement target_placement_;
  std::shared_ptr<TransferSlot> transfer_slot_;
  std::uint64_t target_epoch_ = 0, transfer_submitted_ = 0, transfer_received_ = 0;
  std::uint64_t transfer_source_request_ = 0, transfer_pairing_revision_ = 0;  // of the newest request
  std::optional<Transferred> transferred_;
  std::string transfer_error_;
  geometry::Vertices target_shown_;  // the target as drawn (placed beside the mesh)
  std::unique_ptr<geometry::Bvh> target_bvh_;
  bool target_dirty_ = true, target_pick_stale_ = true, show_target_ = true;
  int active_pair_ = 0;

  viewer::LatestWorker<Transferred> transfer_worker_;
  viewer::LatestWorker<Solved> worker_;  // last: joined first, before what jobs use
};

}  // namespace lapis::deform_app
