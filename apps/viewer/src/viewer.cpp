#define GL_GLEXT_PROTOTYPES
#include "lapis/viewer/viewer.h"

// GLFW's header brings in GL/gl.h, which glext.h needs first.
#include <GLFW/glfw3.h>

#include <GL/glext.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>
#include <imgui_internal.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <thread>

#include "lapis/core/atomic_file.h"
#include "lapis/core/error.h"
#include "lapis/viewer/renderer.h"
#include "picture.h"

namespace lapis::viewer {

namespace {
constexpr long kSettleFrames = 3;            // frames drawn after input (ImGui hover, releases)
constexpr double kBusyRedrawSeconds = 0.25;  // redraw period while the app's worker runs
constexpr double kIdleRedrawSeconds = 1.0;   // and while nothing happens (overlay clock)

// A run that ends by itself once the app is idle (an automatic screenshot, or a headless or
// replayed run told to exit): it should not wait for input that will not come.
bool finishing_run(const lapis::viewer::ViewerOptions& o) {
  const bool replayed = !o.replay.empty();
  return o.headless || (replayed && (o.exit_after_replay || !o.screenshot.empty()));
}

using Clock = std::chrono::steady_clock;
thread_local std::string last_glfw_error;

void glfw_error(int code, const char* message) {
  last_glfw_error = std::string(message ? message : "unknown") + " (GLFW error " + std::to_string(code) + ")";
}

}  // namespace

struct Viewer::Window {
  GLFWwindow* handle = nullptr;
  std::unique_ptr<Renderer> renderer;
  Clock::time_point start = Clock::now();
  bool imgui = false;

  ~Window() {
    renderer.reset();  // needs the context
    if (imgui) {
      ImGui_ImplOpenGL3_Shutdown();
      ImGui_ImplGlfw_Shutdown();
      ImGui::DestroyContext();
    }
    if (handle) glfwDestroyWindow(handle);
    glfwTerminate();
  }
};

// GLFW callbacks: turn GLFW's calls into InputEvents on the viewer stored as user pointer.
struct GlfwCallbacks {
  static Viewer& viewer(GLFWwindow* w) { return *static_cast<Viewer*>(glfwGetWindowUserPointer(w)); }
  static bool live(Viewer& v) { return !v.replaying(); }  // real input is ignored during a replay

  static void cursor(GLFWwindow* w, double x, double y) {
    Viewer& v = viewer(w);
    if (!live(v)) return;
    InputEvent e{EventType::MouseMove};
    e.x = x, e.y = y;
    v.cursor_seen_ = true;
    v.record(e);
    v.dispatch(e);
  }
  static void button(GLFWwindow* w, int button, int action, int mods) {
    Viewer& v = viewer(w);
    if (!live(v)) return;
    InputEvent e{EventType::MouseButton};
    // Where the pointer was at the press: the last motion handled before it. GLFW's query
    // asks the server for where it is now, which on a loaded machine is several queued
    // motions later (a stroke then began 60 px down, off the scalp).
    if (v.cursor_seen_)
      e.x = v.cursor_.x(), e.y = v.cursor_.y();
    else
      glfwGetCursorPos(w, &e.x, &e.y);
    e.button = button, e.action = action, e.mods = mods;
    v.record(e);
    v.dispatch(e);
  }
  static void scroll(GLFWwindow* w, double dx, double dy) {
    Viewer& v = viewer(w);
    if (!live(v)) return;
    InputEvent e{EventType::Scroll};
    e.x = dx, e.y = dy;
    v.record(e);
    v.dispatch(e);
  }
  static void key(GLFWwindow* w, int key, int, int action, int mods) {
    Viewer& v = viewer(w);
    if (!live(v)) return;
    InputEvent e{EventType::Key};
    e.key = key, e.action = action, e.mods = mods;
    v.record(e);
    v.dispatch(e);
  }
  static void character(GLFWwindow* w, unsigned int c) {
    Viewer& v = viewer(w);
    if (!live(v)) return;
    InputEvent e{EventType::Char};
    e.codepoint = c;
    v.record(e);
    v.dispatch(e);
  }
  static void resize(GLFWwindow* w, int width, int height) {
    Viewer& v = viewer(w);
    v.width_ = width, v.height_ = height;
  }
};

Viewer::Viewer(ViewerOptions options) : options_(std::move(options)) {
  if (!options_.replay.empty()) {
    replay_ = EventLog::load(options_.replay);
    // Replays reproduce pixel coordinates: use the recorded window size.
    if (replay_->width > 0 && replay_->height > 0) options_.width = replay_->width, options_.height = replay_->height;
  }
}

Viewer::~Viewer() = default;

double Viewer::time() const {
  return window_ ? std::chrono::duration<double>(Clock::now() - window_->start).count() : 0.0;
}

bool Viewer::button_down(int button) const { return button >= 0 && button < 8 && buttons_[button]; }

CameraMatrices Viewer::camera_matrices() const { return camera_.matrices(width_, height_); }

void Viewer::frame_scene() {
  Eigen::Vector3d lo, hi;
  if (scene_.bounds(lo, hi)) camera_.frame(lo, hi);
}

void Viewer::flash(std::string message, Tone tone) {
  const char* kind = tone == Tone::Error ? "error: " : tone == Tone::Warning ? "warning: " : "";
  std::fprintf(stderr, "%s: %s%s\n", options_.title.c_str(), kind, message.c_str());  // logs of batch runs
  flash_ = {tone, std::move(message)};
  flash_shown_at_ = time();
  flash_until_ = tone == Tone::Error || tone == Tone::Warning ? std::numeric_limits<double>::infinity() : time() + 4.0;
}

bool Viewer::last_frame_drew_scene() const {
  return !(window_ && window_->renderer && window_->renderer->stats().reused);
}

std::filesystem::path Viewer::screenshot_path() const {
  if (!options_.screenshot.empty()) return options_.screenshot;
  return default_screenshot_.empty() ? std::filesystem::path("screenshot.png") : default_screenshot_;
}

void Viewer::close() {
  if (window_ && window_->handle) glfwSetWindowShouldClose(window_->handle, GLFW_TRUE);
}

void Viewer::record(const InputEvent& e) {
  if (options_.record.empty()) return;
  InputEvent r = e;
  r.frame = frame_;
  r.time = time();
  recording_.events.push_back(r);
}

void Viewer::wake() { glfwPostEmptyEvent(); }

void Viewer::dispatch(const InputEvent& e) {
  last_input_frame_ = frame_;
  ++handled_events_;
  handled_buttons_ += e.type == EventType::MouseButton;
  handled_keys_ += e.type == EventType::Key;
  // A click or a key press after an error or a warning was read dismisses it.
  const bool press = (e.type == EventType::MouseButton || e.type == EventType::Key) && e.action == GLFW_PRESS;
  if (press && std::isinf(flash_until_) && time() - flash_shown_at_ >= 2.0) flash_until_ = time();
  ImGuiIO& io = ImGui::GetIO();
  GLFWwindow* w = window_ ? window_->handle : nullptr;
  const bool keyboard = e.type == EventType::Key || e.type == EventType::Char;
  // Keys act where the pointer is: over a panel they go to it (its focused field, its tabbing),
  // over the 3D view to the app, and a panel's field loses the keyboard, so a Tab or a digit
  // typed over the view never lands in a field the last click left focused.
  const bool keys_to_gui = keyboard && over_gui(cursor_.x(), cursor_.y());
  if (keyboard && !keys_to_gui && GImGui && (io.WantCaptureKeyboard || GImGui->NavWindow))
    ImGui::SetWindowFocus(nullptr);
  switch (e.type) {
    case EventType::MouseMove:
      cursor_ = {e.x, e.y};
      break;
    case EventType::MouseButton:
      cursor_ = {e.x, e.y};
      if (e.button >= 0 && e.button < 8) buttons_[e.button] = e.action == GLFW_PRESS;
      if (w) ImGui_ImplGlfw_MouseButtonCallback(w, e.button, e.action, e.mods);
      break;
    case EventType::Scroll:
      if (w) ImGui_ImplGlfw_ScrollCallback(w, e.x, e.y);
      break;
    case EventType::Key:
      // A release always reaches the panels, so none of their keys stays down.
      if (w && (keys_to_gui || e.action == GLFW_RELEASE)) ImGui_ImplGlfw_KeyCallback(w, e.key, 0, e.action, e.mods);
      break;
    case EventType::Char:
      if (w && keys_to_gui) ImGui_ImplGlfw_CharCallback(w, e.codepoint);
      break;
    case EventType::Resize:
    case EventType::Idle:
      break;
  }
  if (keys_to_gui && io.WantCaptureKeyboard) return;
  // Mouse events go to the panels when they are over one (tested at the event's own
  // position: io.WantCaptureMouse still describes the previous frame's cursor). A drag that
  // started in the 3D view stays with the app until its release, even across a panel.
  if (e.type == EventType::MouseButton) {
    if (e.action == GLFW_PRESS) {
      if (over_gui(e.x, e.y)) return;
      ++app_drags_;
    } else if (e.action == GLFW_RELEASE) {
      if (app_drags_ == 0) return;
      --app_drags_;
    }
  } else if ((e.type == EventType::MouseMove && app_drags_ == 0 && over_gui(e.x, e.y)) ||
             (e.type == EventType::Scroll && over_gui(cursor_.x(), cursor_.y()))) {
    return;
  }
  if (app_ && app_->on_event(*this, e)) return;
  handle_camera(e);
}

bool Viewer::over_gui(double x, double y) const {
  const ImVec2 p(static_cast<float>(x), static_cast<float>(y));
  for (const ImGuiWindow* w : GImGui->Windows)
    if (w->WasActive && !w->Hidden && !(w->Flags & ImGuiWindowFlags_NoMouseInputs) && w->Rect().Contains(p))
      return true;
  return false;
}

void Viewer::handle_camera(const InputEvent& e) {
  if (e.type == EventType::MouseButton && e.action == GLFW_PRESS) drag_from_ = {e.x, e.y};
  if (e.type == EventType::MouseMove) {
    const Eigen::Vector2d d = Eigen::Vector2d(e.x, e.y) - drag_from_;
    if (buttons_[GLFW_MOUSE_BUTTON_RIGHT])
      camera_.orbit(d.x(), d.y());
    else if (buttons_[GLFW_MOUSE_BUTTON_MIDDLE])
      camera_.pan(d.x(), d.y(), height_);
    drag_from_ = {e.x, e.y};
  }
  if (e.type == EventType::Scroll) camera_.zoom(e.y);
  if (e.type == EventType::Key && e.action == GLFW_PRESS && e.key == GLFW_KEY_F && e.mods == 0) frame_scene();
  if (e.type == EventType::Key && e.action == GLFW_PRESS && e.key == GLFW_KEY_Q && e.mods == GLFW_MOD_CONTROL)
    user_asked_to_close_ = true, close();
  if (e.type == EventType::Key && e.action == GLFW_PRESS && e.key == GLFW_KEY_P && e.mods == GLFW_MOD_CONTROL)
    request_screenshot(screenshot_path());
}

// What the last frame's time went to: the scene drawn again (its size, the MSAA samples: what
// software GL pays for) or the picture of an unchanged scene reused (then the panels).
std::string Viewer::frame_limit() const {
  const RenderStats s = window_ && window_->renderer ? window_->renderer->stats() : RenderStats{};
  if (s.reused) return "scene unchanged: panels only";
  char buf[64];
  std::snprintf(buf, sizeof buf, "scene drawn: %.0fK triangles", s.triangles / 1000.0);
  std::string out = buf;
  if (s.strips) out += ", " + std::to_string(s.strips) + " strips";
  return out + ", " + std::to_string(options_.msaa_samples) + "x MSAA";
}

void Viewer::draw_overlay() {
  ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.45f);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                 ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                                 ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoInputs;
  if (ImGui::Begin("##overlay", nullptr, flags)) {
    ImGui::Text("frame %.1f ms (%.0f fps), %s", last_frame_ms_, last_frame_ms_ > 0 ? 1000.0 / last_frame_ms_ : 0.0,
                frame_limit().c_str());
    const float wrap_at = 0.6f * static_cast<float>(width_);  // long lines stay off the right-hand panels
    for (const auto& line : overlay_lines_) tone_text(line.tone, line.text, wrap_at);
    if (!flash_.text.empty() && time() < flash_until_) tone_text(flash_.tone, flash_.text, wrap_at);
  }
  ImGui::End();
  overlay_lines_.clear();
}

void Viewer::take_screenshot(const std::filesystem::path& path) {
  Image image;
  image.width = width_, image.height = height_;
  image.rgba.resize(static_cast<size_t>(width_) * static_cast<size_t>(height_) * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  std::vector<std::uint8_t> raw(image.rgba.size());
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, raw.data());
  const size_t row = static_cast<size_t>(width_) * 4;
  for (int y = 0; y < height_; ++y)  // GL's first row is the bottom one
    std::copy_n(raw.data() + static_cast<size_t>(height_ - 1 - y) * row, row,
                image.rgba.data() + static_cast<size_t>(y) * row);
  for (size_t k = 3; k < image.rgba.size(); k += 4) image.rgba[k] = 255;
  core::create_parent_directories(path);
  write_png(path, image);
  std::printf("screenshot: %s\n", path.string().c_str());
}

void Viewer::take_picture(const std::filesystem::path& path) {
  app_->prepare_picture(*this);
  const auto start = Clock::now();
  const PictureOptions o{options_.width, options_.height, options_.supersample, options_.msaa_samples,
                         options_.render_tile};
  const Image image = render_picture(*window_->renderer, scene_, camera_.matrices(o.width, o.height), o);
  core::create_parent_directories(path);
  write_png(path, image);
  std::printf("render: %s (%dx%d, %dx%d samples per pixel, %.1f s)\n", path.string().c_str(), o.width, o.height,
              o.supersample, o.supersample, std::chrono::duration<double>(Clock::now() - start).count());
}

void Viewer::report_ready(bool busy) {
  const std::string state = " events=" + std::to_string(handled_events_) +
                            " buttons=" + std::to_string(handled_buttons_) + " keys=" + std::to_string(handled_keys_) +
                            " busy=" + (busy ? "1" : "0") + " asking=" + (app_->asking() ? "1" : "0");
  if (state == last_ready_) return;
  last_ready_ = state;
  core::write_file_atomically(options_.ready_file,
                              [&](std::ostream& out) { out << "frame=" << frame_ << state << "\n"; });
}

void Viewer::write_benchmark(const ViewerApp& app) const {
  std::vector<double> ms = frame_ms_;
  nlohmann::json j;
  j["frames"] = ms.size();
  if (!ms.empty()) {
    std::sort(ms.begin(), ms.end());
    j["frame_ms_median"] = ms[ms.size() / 2];
    j["frame_ms_p95"] = ms[std::min(ms.size() - 1, ms.size() * 95 / 100)];
    j["frame_ms_max"] = ms.back();
  }
  j["width"] = width_;
  j["height"] = height_;
  app.benchmark_fields(j);
  core::create_parent_directories(options_.benchmark);
  core::write_file_atomically(options_.benchmark, [&](std::ostream& out) { out << j.dump(2) << "\n"; });
  std::printf("benchmark: %s\n", options_.benchmark.string().c_str());
}

void Viewer::open_window() {
  glfwSetErrorCallback(glfw_error);
  if (!glfwInit())
    throw Error("viewer::Viewer::run(): cannot initialise GLFW: " + last_glfw_error +
                " (no display? run under Xvfb, e.g. xvfb-run -a)");
  window_ = std::make_unique<Window>();
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_SAMPLES, options_.msaa_samples);
  glfwWindowHint(GLFW_VISIBLE, options_.headless ? GLFW_FALSE : GLFW_TRUE);
  window_->handle = glfwCreateWindow(options_.width, options_.height, options_.title.c_str(), nullptr, nullptr);
  if (!window_->handle)
    throw Error("viewer::Viewer::run(): cannot create an OpenGL 3.3 core window: " + last_glfw_error);
  GLFWwindow* w = window_->handle;
  glfwMakeContextCurrent(w);
  glfwSwapInterval(options_.headless ? 0 : 1);
  glfwSetWindowUserPointer(w, this);
  glfwGetFramebufferSize(w, &width_, &height_);

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini next to the user's files
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(w, /*install_callbacks=*/false);
  ImGui_ImplOpenGL3_Init("#version 330");
  window_->imgui = true;
  glfwSetCursorPosCallback(w, GlfwCallbacks::cursor);
  glfwSetMouseButtonCallback(w, GlfwCallbacks::button);
  glfwSetScrollCallback(w, GlfwCallbacks::scroll);
  glfwSetKeyCallback(w, GlfwCallbacks::key);
  glfwSetCharCallback(w, GlfwCallbacks::character);
  glfwSetFramebufferSizeCallback(w, GlfwCallbacks::resize);
  glfwSetWindowCloseCallback(w, [](GLFWwindow* window) { GlfwCallbacks::viewer(window).user_asked_to_close_ = true; });
  window_->renderer = make_gl_renderer(options_.frame_cache);
  recording_.width = width_, recording_.height = height_;
}

// Redraw on demand. Drawing the same picture again costs a software renderer most of both
// cores, which the app's worker needs: with nothing new (no input for a few frames, no
// replay or screenshot pending, no change in busy state) wait for input or a wake()
// instead, redrawing a few times a second while the app works so its progress shows.
// A replay does the same between its events: idle frames are skipped, and while the app
// works they come a few a second, so its worker is not starved by the renderer.
void Viewer::wait_for_next_frame(bool busy) {
  const bool settled = frame_ - last_input_frame_ > kSettleFrames && busy == was_busy_;
  if (replaying()) {
    const InputEvent& next = replay_->events[replay_next_];
    const long next_frame = next.frame + replay_delay_;
    const bool held_until_idle = next.type == EventType::Idle && next_frame <= frame_ && busy;
    if (settled && (next_frame > frame_ || held_until_idle)) {
      if (busy)
        glfwWaitEventsTimeout(kBusyRedrawSeconds);
      else
        frame_ = next_frame;
    }
    glfwPollEvents();
  } else if (settled && !pending_screenshot_ && frame_ >= kSettleFrames && !(finishing_run(options_) && !busy)) {
    glfwWaitEventsTimeout(busy ? kBusyRedrawSeconds : kIdleRedrawSeconds);
  } else {
    glfwPollEvents();
  }
  was_busy_ = busy;
}

void Viewer::play_due_events() {
  if (!replay_) return;
  while (replay_next_ < replay_->events.size() && replay_->events[replay_next_].frame + replay_delay_ <= frame_) {
    if (replay_->events[replay_next_].type == EventType::Idle) {
      // Hold here while the app works; what follows is delayed by the frames waited.
      if (app_->busy()) {
        ++replay_delay_;
        break;
      }
      ++replay_next_;
      continue;
    }
    dispatch(replay_->events[replay_next_++]);
  }
}

void Viewer::draw_frame() {
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  // The app's idea of the cursor (replayed or real) is what ImGui sees too.
  ImGuiIO& io = ImGui::GetIO();
  io.MousePos = ImVec2(static_cast<float>(cursor_.x()), static_cast<float>(cursor_.y()));
  for (int b = 0; b < 3; ++b) io.MouseDown[b] = io.MouseDown[b] || buttons_[b];
  if (replay_)
    for (int b = 0; b < 3; ++b) io.MouseDown[b] = buttons_[b];
  ImGui::NewFrame();

  app_->on_frame(*this);
  app_->on_gui(*this);
  draw_overlay();
  ImGui::Render();
  window_->renderer->render(scene_, camera_matrices(), width_, height_);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());

  if (pending_screenshot_) {
    take_screenshot(*pending_screenshot_);
    pending_screenshot_.reset();
  }
}

bool Viewer::close_when_done() {
  const bool replay_done = !replaying();
  const bool auto_shot = !options_.screenshot.empty() && (replay_ || options_.headless);
  // A headless run has nobody to close its window: it ends once idle, with or without a
  // screenshot (it used to spin a core forever without one).
  if (!(replay_done && (auto_shot || options_.headless || (replay_ && options_.exit_after_replay)) && frame_ >= 3))
    return true;
  GLFWwindow* w = window_->handle;
  if (app_->busy()) {
    if (idle_since_replay_ < 0) idle_since_replay_ = time();
    if (time() - idle_since_replay_ > options_.idle_timeout_s) {
      std::fprintf(stderr, "viewer: the app stayed busy for %.0f s after the replay; giving up\n",
                   options_.idle_timeout_s);
      glfwSetWindowShouldClose(w, GLFW_TRUE);
      return false;
    }
  } else if (++idle_frames_after_replay_ >= 2) {
    // The second idle frame: panels that size themselves to their content (the overlay)
    // take one frame to fit what the result just changed.
    if (auto_shot) take_screenshot(options_.screenshot), options_.screenshot.clear();
    if (!options_.render.empty()) take_picture(options_.render), options_.render.clear();
    if (options_.exit_after_replay || options_.headless) glfwSetWindowShouldClose(w, GLFW_TRUE);
  }
  return true;
}

void Viewer::keep_open_if_app_asks() {
  GLFWwindow* w = window_->handle;
  const bool interactive = !options_.headless && !replay_;
  if (interactive && user_asked_to_close_ && glfwWindowShouldClose(w) && !app_->may_close(*this))
    glfwSetWindowShouldClose(w, GLFW_FALSE);
  user_asked_to_close_ = false;
}

// Returns the app's exit status (a failed export on exit, say).
int Viewer::finish_run() {
  app_->on_exit(*this);
  const int status = app_->exit_status();
  if (!options_.record.empty()) {
    recording_.save(options_.record);
    std::printf("recorded %zu events: %s\n", recording_.events.size(), options_.record.string().c_str());
  }
  if (!options_.benchmark.empty()) write_benchmark(*app_);
  app_ = nullptr;
  window_.reset();
  return status;
}

int Viewer::run(ViewerApp& app) {
  app_ = &app;
  open_window();
  app.on_start(*this);
  if (options_.orbit) {
    constexpr double kDegree = 3.14159265358979323846 / 180;
    camera_.yaw = options_.orbit->x() * kDegree;
    camera_.pitch = options_.orbit->y() * kDegree;
  }
  int exit_code = 0;
  idle_since_replay_ = -1;
  idle_frames_after_replay_ = 0;
  was_busy_ = false;
  while (!glfwWindowShouldClose(window_->handle)) {
    wait_for_next_frame(app.busy());
    const auto frame_start = Clock::now();
    play_due_events();
    draw_frame();
    if (!close_when_done()) exit_code = 1;
    keep_open_if_app_asks();
    glfwSwapBuffers(window_->handle);
    app.on_frame_shown(*this);
    if (!options_.ready_file.empty()) report_ready(app.busy());
    // The frame's own work (events to swap), not the waits between on-demand frames.
    last_frame_ms_ = std::chrono::duration<double, std::milli>(Clock::now() - frame_start).count();
    frame_ms_.push_back(last_frame_ms_);
    ++frame_;
  }
  exit_code = std::max(exit_code, finish_run());
  return exit_code;
}

}  // namespace lapis::viewer
