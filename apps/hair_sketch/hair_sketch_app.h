// lapis-hair-sketch: sketch a hairstyle on a head and watch the strands follow (thesis ch. 4).
// The app only wires the viewer's input and panels to the hair_sketch module: strokes become
// document commands (stroke_commands.h), the field and strands are brought up to date by a
// LiveHairstyle on a worker thread, and the newest strands are drawn when they are ready.
#pragma once

#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "lapis/hair_sketch/document.h"
#include "lapis/hair_sketch/head.h"
#include "lapis/hair_sketch/live_hairstyle.h"
#include "lapis/hair_sketch/strand_occlusion.h"
#include "lapis/viewer/adaptive_budget.h"
#include "lapis/viewer/latest_worker.h"
#include "lapis/viewer/panel_column.h"
#include "lapis/viewer/viewer.h"

namespace lapis::hair_app {

using namespace lapis::hair_sketch;
using namespace lapis::hair_field;

enum class Tool { StreamCurve, DividingCurve, Ponytail, Hint, Tilt, Select, Cut, Region };
inline constexpr Tool kTools[] = {Tool::StreamCurve, Tool::DividingCurve, Tool::Ponytail, Tool::Hint,
                                  Tool::Tilt,        Tool::Select,        Tool::Cut,      Tool::Region};
const char* tool_name(Tool t);

// What the worker hands back for one document revision.
struct Regrowth {
  std::uint64_t revision = 0;
  std::uint64_t settings_epoch = 0;
  LiveUpdate update;
  Grid grid;
  std::shared_ptr<const Field> field;  // for glyphs
  double worker_ms = 0;                // the whole job on the worker
  double queued_ms = 0;                // from the request to the job's start
  std::chrono::steady_clock::time_point finished;
  // > 0: a preview, the strands of every preview_stride-th root only (LiveHairstyle::preview):
  // the strands the window draws. The job's whole result follows it.
  int preview_stride = 0;
  // The job stopped after its preview: a newer edit was waiting, and growing the rest for this
  // one would only delay it. No strands; `update.strands` is the storage the job was given.
  bool superseded = false;
};

// Holds a job back until the window has shown its preview, so that the rest of the growth
// does not compete with the preview's frame for the cores. Opens by itself after a while, so
// nothing waits on a window that draws no more.
class FrameGate {
 public:
  void open();
  void wait();

 private:
  std::mutex mutex_;
  std::condition_variable opened_;
  bool open_ = false;
};

// Where one edit's time went, from the stroke's release to its strands on screen (--benchmark).
struct EditStages {
  double total_ms = 0;              // release → the frame that shows the strands drawn
  double style_solve_ms = 0;        // the field with the style's constraints
  double avoidance_ms = 0;          // finding scalp avoidance's constraints (§4.6)
  double avoidance_solve_ms = 0;    // and the second solve with them
  int iterations = 0;               // multigrid iterations of both solves (0: direct)
  std::vector<std::string> solves;  // each solve's report: what ran, its update and solve times
  double growth_ms = 0, detail_ms = 0, occlusion_ms = 0;
  double display_ms = 0;   // the strands decimated, coloured and lit (occlusion_ms of it) for the renderer
  double draw_ms = 0;      // the rest of the frame that drew them first (upload and drawing)
  double waiting_ms = 0;   // the rest: queued behind an older job, the frame that hands over
  double queued_ms = 0;    // of it: from the request to the job's start
  double handover_ms = 0;  // of it: from the job's end to the frame that takes its strands
  // With a preview, the strands drawn (total_ms) are those of every k-th root; then the rest grow.
  bool preview = false;
  double rest_ms = 0;         // the rest's growth and detail, after the preview's frame
  double all_strands_ms = 0;  // release → every strand received (= total_ms less the drawing without a preview)
  bool redrawn = false;       // the whole set showed other strands than the preview (a new stride)
};

// How strands are drawn: ribbons (tapered, anti-aliased, self-shadowed: the look of the
// hair) or one-pixel lines (the cheapest, for very large counts on software GL).
enum class StrandLook { Ribbons, Lines };

struct AppPaths {
  std::filesystem::path session;   // Ctrl+S / Ctrl+O
  std::filesystem::path autosave;  // every minute and on exit
  std::filesystem::path export_hair, export_obj;
  bool export_on_exit = false;  // batch runs: write the exports when the app closes
};

class HairSketchApp final : public viewer::ViewerApp {
 public:
  HairSketchApp(Head head, Hairstyle style, AppPaths paths);
  ~HairSketchApp() override;
  // Strand segments drawn, pinned (0: all). Default: adapted to the frame time in a window
  // (from 100K), all headless.
  void set_drawn_segments(long segments) { strand_budget_.pin(segments); }

  void on_start(viewer::Viewer& v) override;
  bool on_event(viewer::Viewer& v, const viewer::InputEvent& e) override;
  void on_frame(viewer::Viewer& v) override;
  void on_frame_shown(viewer::Viewer& v) override;
  void on_gui(viewer::Viewer& v) override;
  void on_exit(viewer::Viewer& v) override;
  bool busy() const override;
  void prepare_picture(viewer::Viewer& v) override;
  void set_strand_look(StrandLook look) { strand_look_ = look; }
  int exit_status() const override { return exit_status_; }
  void benchmark_fields(nlohmann::json& j) const override;

  const Document& document() const { return document_; }

 private:
  // Input.
  void begin_stroke(viewer::Viewer& v, const Eigen::Vector2d& p);
  void extend_stroke(viewer::Viewer& v, const Eigen::Vector2d& p);
  void finish_stroke(viewer::Viewer& v);
  void warn_if_tail_too_thin(viewer::Viewer& v, const hair_sketch::StylePrimitive& p);
  void select_at(viewer::Viewer& v, const Eigen::Vector2d& p);
  bool handle_key(viewer::Viewer& v, const viewer::InputEvent& e);
  void execute(viewer::Viewer& v, Command command);
  void undo(viewer::Viewer& v);
  void begin_edit(double time);  // after a document change: regrow, the scene held meanwhile
  void end_scene_hold(viewer::Viewer& v);
  void redo(viewer::Viewer& v);
  void delete_selected(viewer::Viewer& v);
  void set_details(viewer::Viewer& v, std::vector<StrandDetail> details, const std::string& name);
  void add_cut_line(viewer::Viewer& v);
  void paint_region(viewer::Viewer& v, const Eigen::Vector2d& p);

  // Files.
  void save(viewer::Viewer& v, const std::filesystem::path& path);
  void load(viewer::Viewer& v, const std::filesystem::path& path);
  bool export_strands(viewer::Viewer& v);  // false (and the reason flashed) on failure
  void autosave_if_due(viewer::Viewer& v);

  // Engine.
  void settings_changed();
  void request_regrowth();
  void receive_regrowth(viewer::Viewer& v);
  EditStages stages(const Regrowth& r, double display_start, double now) const;

  // Drawing (hair_scene.cpp) and panels (hair_panels.cpp).
  void update_head_item(viewer::Viewer& v);
  // `subset_stride` > 0: the strands are those of every subset_stride-th root (a preview).
  void update_strand_item(viewer::Viewer& v, const Strands& strands, int subset_stride = 0);
  int preview_stride() const;              // the preview's stride for the next regrowth; 0: none
  void redraw_strands(viewer::Viewer& v);  // the strands on screen again (a new look or budget)
  void receive_preview(viewer::Viewer& v, Regrowth r);
  void update_curve_items(viewer::Viewer& v);
  void update_preview_item(viewer::Viewer& v);
  void update_glyph_item(viewer::Viewer& v);
  void draw_toolbar(viewer::Viewer& v, viewer::PanelColumn& column);
  void draw_primitive_panel(viewer::Viewer& v, viewer::PanelColumn& column);
  void draw_settings_panel(viewer::Viewer& v);
  void draw_file_panel(viewer::Viewer& v, viewer::PanelColumn& column);
  void draw_detail_panel(viewer::Viewer& v, viewer::PanelColumn& column);
  void draw_overlay(viewer::Viewer& v);

  Head head_;
  Document document_;
  AppPaths paths_;
  Grid grid_;  // of the current settings: strokes are resampled at its spacing

  Tool tool_ = Tool::StreamCurve;
  int selected_ = -1;
  int selected_detail_ = -1;
  bool symmetric_ = false;  // new primitives get a mirrored twin (M)
  std::set<int> painted_;   // head vertices painted by the region brush during a drag
  float region_brush_pixels_ = 30;
  int exit_status_ = 0;  // 1 when the export on exit failed
  std::set<int> hidden_;
  bool drawing_ = false;
  Stroke stroke_;                                           // the stroke being drawn
  std::vector<Stroke> ponytail_strokes_;                    // spine, cross section, profile a, profile b
  std::vector<geometry::CameraMatrices> ponytail_cameras_;  // each one's camera
  std::vector<Eigen::Vector3d> preview_;                    // 3D preview of the stroke's curve

  // Display.
  bool show_scalp_ = false, show_glyphs_ = false, show_curves_ = true, show_strands_ = true;
  Eigen::Vector3f root_color_{0.16f, 0.09f, 0.05f}, tip_color_{0.55f, 0.36f, 0.20f};
  float strand_width_ = 1.5f;  // pixels at the root
  StrandLook strand_look_ = StrandLook::Ribbons;
  bool self_shadowing_ = true;
  double occlusion_ms_ = 0;  // the last self-shadowing of the strands on screen
  // Strand segments drawn (display_strands, strand_display.h; 0: every segment), adapted to keep
  // frames near 80 ms: software rendering of 20K full strands (4M segments, 4× MSAA) takes
  // two seconds a frame. Headless runs (screenshots, demos) draw everything.
  viewer::AdaptiveBudget strand_budget_{100000};
  int shown_strands_ = 0;
  int shown_stride_ = 0;  // every shown_stride_-th strand is drawn (display_stride)
  // The preview on screen until its whole set arrives: restyling redraws it, not the older set.
  struct ShownPreview {
    std::uint64_t revision = 0, settings_epoch = 0;
    Strands strands;
    int stride = 0;
  };
  std::optional<ShownPreview> shown_preview_;
  std::shared_ptr<FrameGate> preview_gate_;  // the running job's, opened once its preview is shown
  long preview_drawn_in_frame_ = -1;
  bool curves_dirty_ = true, head_dirty_ = true;

  // Worker: regrowth never blocks input; the previous strands stay until new ones arrive.
  struct EngineSlot {
    std::unique_ptr<LiveHairstyle> live;
    std::uint64_t epoch = ~0ull;
  };
  std::shared_ptr<EngineSlot> engine_ = std::make_shared<EngineSlot>();
  std::uint64_t settings_epoch_ = 0;
  std::uint64_t requested_revision_ = ~0ull, requested_epoch_ = ~0ull;
  std::optional<Regrowth> last_;
  Strands spare_strands_;  // replaced on screen; the next regrowth writes into them
  std::string engine_error_;
  double last_edit_time_ = 0;
  // While an edit's strands are on their way, the scene keeps its last picture (the stroke as
  // drawn, the old curves): redrawing it costs a software-GL frame that competes with the
  // solve for the cores. The curves and the strands then change in one frame.
  double scene_held_since_ = -1;
  double last_autosave_ = 0;
  std::vector<EditStages> edits_;          // edit → strands on screen, by stage, for --benchmark
  long edit_drawn_in_frame_ = -1;          // the frame that first draws the last edit's strands
  viewer::LatestWorker<Regrowth> worker_;  // last: joined first, before what jobs use
};

}  // namespace lapis::hair_app
