#include <doctest/doctest.h>

#include <algorithm>
#include <fstream>

#include "app_runner.h"
#include "lapis/viewer/input_events.h"

using namespace lapis;
using namespace lapis::apps_test;

namespace {
const std::string kView = LAPIS_VIEW_EXE;
const std::string kMesh = std::string(LAPIS_SOURCE_DIR) + "/assets/external/cactus.off";
}  // namespace

TEST_CASE("apps: lapis-view renders a mesh headless into a screenshot") {
  const fs::path png = scratch_dir() / "view.png";
  REQUIRE(run_under_xvfb(kView + " " + kMesh + " --headless --size 640x480 --screenshot " + png.string()) == 0);
  const viewer::Image img = viewer::read_png(png);
  CHECK(img.width == 640);
  CHECK(img.height == 480);
  const double fg = foreground_fraction(img);
  CHECK(fg > 0.03);  // the mesh is there
  CHECK(fg < 0.9);   // and framed, not filling everything
}

TEST_CASE("apps: a replayed zoom changes the picture the way zooming should") {
  const fs::path dir = scratch_dir();
  viewer::EventLog log;
  log.width = 640, log.height = 480;
  for (int k = 0; k < 6; ++k) {
    viewer::InputEvent e{viewer::EventType::MouseMove};
    e.frame = 2 + k, e.x = 320, e.y = 240;
    log.events.push_back(e);
    viewer::InputEvent s{viewer::EventType::Scroll};
    s.frame = 2 + k, s.y = 1;  // wheel forward: closer
    log.events.push_back(s);
  }
  log.save(dir / "zoom.json");
  REQUIRE(run_under_xvfb(kView + " " + kMesh + " --headless --size 640x480 --screenshot " +
                         (dir / "far.png").string()) == 0);
  REQUIRE(run_under_xvfb(kView + " " + kMesh + " --headless --replay " + (dir / "zoom.json").string() +
                         " --exit-after-replay --screenshot " + (dir / "near.png").string()) == 0);
  const double far = foreground_fraction(viewer::read_png(dir / "far.png"));
  const double near = foreground_fraction(viewer::read_png(dir / "near.png"));
  CHECK(near > 1.5 * far);
}

TEST_CASE("apps: xdotool drives a real window and the recording captures it") {
  const fs::path dir = scratch_dir();
  const fs::path rec = dir / "recorded.json";
  // A visible window under Xvfb: xdotool finds it once it has drawn, presses the right button,
  // drags (orbit), scrolls, and quits with Ctrl+Q once those arrived, so the app exits cleanly
  // and writes the recording.
  const std::string body = kView + " " + kMesh + " --size 640x480 --record " + rec.string() + " --ready-file " +
                           (dir / "view.ready").string() +
                           " &\napp=$!\n"
                           "window lapis-view || { kill $app; exit 3; }\n"
                           "mark; xdotool mousemove --window $w 300 240 mousedown 3 mousemove --window $w 360 250"
                           " mousemove --window $w 420 260 mouseup 3 click 4 click 4\n"
                           // 3 moves, 2 buttons, 2 wheel clicks (GLFW scrolls); in order, so ctrl+q comes after them
                           "wait_ready \"[ \\$buttons -ge $((mark_buttons + 2)) ] && [ \\$events -ge $((mark_events + "
                           "6)) ]\" || { kill $app; exit 4; }\n"
                           "xdotool key --window $w ctrl+q; wait $app\n";
  REQUIRE(run_under_xvfb(ready_script(dir / "view.sh", dir / "view.ready", body)) == 0);
  const viewer::EventLog log = viewer::EventLog::load(rec);
  int presses = 0, releases = 0, scrolls = 0, moves = 0;
  for (const auto& e : log.events) {
    if (e.type == viewer::EventType::MouseButton && e.button == 1) (e.action == 1 ? presses : releases)++;
    if (e.type == viewer::EventType::Scroll) ++scrolls;
    if (e.type == viewer::EventType::MouseMove) ++moves;
  }
  CHECK(presses == 1);  // GLFW's right button is 1; X's button 3
  CHECK(releases == 1);
  CHECK(scrolls == 2);
  CHECK(moves >= 2);
}

TEST_CASE("apps: lapis-view --headless without a screenshot exits once it has drawn") {
  // It used to wait for a window close that a hidden window never gets, spinning a core.
  REQUIRE(run_under_xvfb("timeout 120 " + kView + " " + kMesh + " --headless --size 320x240") == 0);
}

namespace {
std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
}  // namespace

TEST_CASE("apps: every app reports a malformed command line in one line and exits 2, --help exits 0") {
  const fs::path dir = scratch_dir();
  for (const std::string exe : {LAPIS_VIEW_EXE, LAPIS_DEFORM_APP_EXE, LAPIS_MERGE_APP_EXE, LAPIS_HAIR_APP_EXE}) {
    const std::string name = fs::path(exe).filename().string();
    CAPTURE(name);
    const fs::path err = dir / (name + ".err");
    // Neither needs a display: both fail or print before any window opens.
    CHECK(run(exe + " --size 10x 2> " + err.string()) == 2);
    const std::string text = slurp(err);
    CHECK(text.find(name + ": viewer: --size expects WIDTHxHEIGHT") == 0);
    CHECK(std::count(text.begin(), text.end(), '\n') == 1);
    CHECK(run(exe + " --help > " + (dir / (name + ".help")).string()) == 0);
    CHECK(slurp(dir / (name + ".help")).find("usage: " + name) == 0);
  }
}
