// The shell every Lapis app runs in: a GLFW window with an OpenGL 3.3 core context and
// MSAA, Dear ImGui, an orbit camera (right-drag orbit, middle-drag pan, wheel zoom, F to
// frame), Ctrl+P screenshot, Ctrl+Q quit, a frame-time overlay, and recording / replay of
// the input stream. `--headless` renders into a hidden window (Xvfb + Mesa work). Apps
// implement ViewerApp; all their logic lives in the modules.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "lapis/viewer/input_events.h"
#include "lapis/viewer/orbit_camera.h"
#include "lapis/viewer/png.h"
#include "lapis/viewer/scene.h"
#include "lapis/viewer/tone.h"

namespace lapis::viewer {

struct ViewerOptions {
  std::string title = "Lapis";
  int width = 1280, height = 800;
  int msaa_samples = 4;
  bool headless = false;             // hidden window, closed once the app is idle (after a
                                     // replay, if any); still needs an X display (Xvfb)
  std::filesystem::path replay;      // replay this event log
  std::filesystem::path record;      // record the input stream to this file on exit
  std::filesystem::path screenshot;  // written when the app is idle (after a replay)
  // A finished picture (--render OUT.png, implies headless): once the app is idle, the scene
  // without panels, as the app prepares it (ViewerApp::prepare_picture), at --size, each pixel
  // averaged from supersample² samples (and MSAA); then the app exits.
  std::filesystem::path render;
  int supersample = 3;
  int render_tile = 0;  // the picture is drawn in tiles of this side (output pixels); 0: the largest
  // --orbit YAW,PITCH (degrees): turns the orbit camera there once the app has placed it
  // (pictures from a chosen side without an event file).
  std::optional<Eigen::Vector2d> orbit;
  bool exit_after_replay = false;   // quit once the replay is over and the app idle
  std::filesystem::path benchmark;  // write frame statistics here on exit
  bool frame_cache = true;          // reuse the picture of an unchanged scene (--no-frame-cache:
                                    // draw it every frame, the baseline of bench/apps)
  double idle_timeout_s = 300;      // give up waiting for a busy app after a replay
  // Readiness for scripts that drive the window (xdotool): rewritten atomically after the
  // first frame and after every frame that handled input or changed the app's busy state, as
  // one line "frame=F events=N buttons=B keys=K busy=0|1 asking=0|1" (input events, mouse
  // button and key events handled so far; asking: the app holds a question open, e.g. about
  // unsaved work on quit). Waiting on it replaces sleeps that a loaded machine outlasts.
  std::filesystem::path ready_file;
};

// Parses the flags every app shares (--headless, --replay F, --record F, --screenshot F,
// --render F, --supersample N, --render-tile N, --orbit YAW,PITCH, --exit-after-replay, --benchmark F, --ready-file F,
// --size WxH,
// --msaa N, --no-frame-cache) and returns the arguments
// it did not consume. Throws UsageError on a flag missing its value or with a malformed one.
std::vector<std::string> parse_viewer_flags(int argc, char** argv, ViewerOptions& options);

class Viewer;

class ViewerApp {
 public:
  virtual ~ViewerApp() = default;
  virtual void on_start(Viewer&) {}
  // An input event ImGui did not take. Return true to consume it (the camera then ignores it).
  virtual bool on_event(Viewer&, const InputEvent&) { return false; }
  // Per-frame update, before drawing: poll workers, update the scene.
  virtual void on_frame(Viewer&) {}
  // After the frame is on screen (its buffers swapped): work that should not slow it down.
  virtual void on_frame_shown(Viewer&) {}
  // ImGui panels.
  virtual void on_gui(Viewer&) {}
  virtual void on_exit(Viewer&) {}
  // True while work whose result should be on screen is pending (replays wait for it).
  virtual bool busy() const { return false; }
  // Sets the scene up for a finished picture (--render): no tool overlays, everything drawn at
  // full quality. Called once, when the app is idle, right before the picture is drawn.
  virtual void prepare_picture(Viewer&) {}
  // Extra fields for the --benchmark report.
  virtual void benchmark_fields(nlohmann::json&) const {}
  // The user asks to quit (Ctrl+Q, the window's close button) in an interactive run (not
  // headless, not replaying). Return false to keep the window open — the app then asks about
  // its unsaved work and quits with Viewer::close(), which does not ask again.
  virtual bool may_close(Viewer&) { return true; }
  // True while such a question is open (the ready file says asking=1 then).
  virtual bool asking() const { return false; }
  // The process exit code the app asks for after on_exit (non-zero: a batch step failed,
  // e.g. the export a headless run was started for).
  virtual int exit_status() const { return 0; }
};

class Viewer {
 public:
  explicit Viewer(ViewerOptions options);
  ~Viewer();
  Viewer(const Viewer&) = delete;
  Viewer& operator=(const Viewer&) = delete;

  // Opens the window and runs until it closes. Returns the process exit code. Throws
  // lapis::Error when no window can be made.
  int run(ViewerApp& app);
  void close();

  Scene& scene() { return scene_; }
  OrbitCamera& camera() { return camera_; }
  CameraMatrices camera_matrices() const;
  void frame_scene();  // fit the camera to the scene's bounds
  int width() const { return width_; }
  int height() const { return height_; }
  const ViewerOptions& options() const { return options_; }

  // The cursor and buttons as the app sees them (replayed or real).
  Eigen::Vector2d cursor() const { return cursor_; }
  bool button_down(int button) const;

  void request_screenshot(const std::filesystem::path& path) { pending_screenshot_ = path; }
  // Where Ctrl+P and an app's screenshot command write: --screenshot when given, else the
  // app's default (next to its document), else screenshot.png in the working directory.
  std::filesystem::path screenshot_path() const;
  void set_default_screenshot(std::filesystem::path path) { default_screenshot_ = std::move(path); }
  // Lines shown in the overlay under the frame time, for this frame, in their tone's colour.
  void overlay(std::string line, Tone tone = Tone::Status) { overlay_lines_.push_back({tone, std::move(line)}); }
  // A message shown in the overlay ("stroke must start on the scalp") and logged to stderr (an
  // error or a warning with its tone first): for 4 s, or, for an error or a warning, until the
  // user clicks or types after reading it (at least 2 s), so a reason is not gone before it is
  // read.
  void flash(std::string message, Tone tone = Tone::Status);

  long frame() const { return frame_; }
  double time() const;  // seconds since start
  bool replaying() const { return replay_.has_value() && replay_next_ < replay_->events.size(); }
  double last_frame_ms() const { return last_frame_ms_; }
  // Whether the last frame drew the scene, not the picture of an unchanged one (frame_cache.h):
  // only such frames tell what drawing costs (an adaptive draw budget goes by them).
  bool last_frame_drew_scene() const;

  // Routes an event as if it came from GLFW (replay and tests use it).
  void dispatch(const InputEvent& event);

  // Wakes the window loop from any thread (a worker finished: show its result now). The loop
  // redraws on demand — on input, on wake(), while replaying, and a few times a second while
  // the app is busy — because software rendering of a full scene takes most of both cores,
  // which the app's worker needs.
  void wake();

 private:
  struct Window;
  void handle_camera(const InputEvent& e);
  bool over_gui(double x, double y) const;  // inside an ImGui window (last frame's layout)
  void draw_overlay();
  std::string frame_limit() const;  // the overlay's note on what the last frame cost
  void keep_open_if_app_asks();     // a user's quit that the app's may_close() declines
  void take_screenshot(const std::filesystem::path& path);
  void take_picture(const std::filesystem::path& path);  // options_.render
  void write_benchmark(const ViewerApp& app) const;
  void record(const InputEvent& e);
  // The steps of run(): open the window with ImGui and the renderer; per frame, wait until
  // something is new, play the replay's due events, draw, and close the window when a replay
  // or headless run is done (returns false when the app stayed busy too long); then finish
  // (returns the app's exit status).
  void open_window();
  void wait_for_next_frame(bool busy);
  void play_due_events();
  void draw_frame();
  bool close_when_done();
  int finish_run();
  void report_ready(bool busy);  // options_.ready_file, when the state changed
  friend struct GlfwCallbacks;

  ViewerOptions options_;
  std::unique_ptr<Window> window_;
  ViewerApp* app_ = nullptr;
  Scene scene_;
  OrbitCamera camera_;
  int width_ = 0, height_ = 0;
  Eigen::Vector2d cursor_ = Eigen::Vector2d::Zero(), drag_from_ = Eigen::Vector2d::Zero();
  bool cursor_seen_ = false;  // a real motion event set cursor_
  bool buttons_[8] = {};
  int app_drags_ = 0;  // buttons pressed outside the panels and not yet released
  long frame_ = 0;
  long last_input_frame_ = 0;  // the frame in which the last input event arrived
  double last_frame_ms_ = 0;
  std::vector<double> frame_ms_;
  struct OverlayLine {
    Tone tone;
    std::string text;
  };
  std::vector<OverlayLine> overlay_lines_;
  OverlayLine flash_;
  double flash_until_ = 0, flash_shown_at_ = 0;
  std::optional<std::filesystem::path> pending_screenshot_;
  std::filesystem::path default_screenshot_;
  bool user_asked_to_close_ = false;  // Ctrl+Q or the close button, this frame
  EventLog recording_;
  std::optional<EventLog> replay_;
  size_t replay_next_ = 0;
  long replay_delay_ = 0;          // frames the replay waited at Idle events
  bool was_busy_ = false;          // the app's busy state in the previous frame
  double idle_since_replay_ = -1;  // when the app was first seen busy after the replay
  int idle_frames_after_replay_ = 0;
  long handled_events_ = 0, handled_buttons_ = 0, handled_keys_ = 0;  // for the ready file
  std::string last_ready_;                                            // its last content but the frame
};

}  // namespace lapis::viewer
