// The hair sketching app, for real: under Xvfb, driven by xdotool, replayed from an event
// file, and rendered headless for every bundled session.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "app_runner.h"
#include "lapis/geometry/camera.h"
#include "lapis/hair_sketch/head.h"
#include "lapis/hair_sketch/session.h"
#include "lapis/hair_sketch/style_field.h"
#include "lapis/viewer/input_events.h"
#include "lapis/viewer/orbit_camera.h"

using namespace lapis;
using namespace lapis::apps_test;

namespace {

const std::string kApp = LAPIS_HAIR_APP_EXE;
const fs::path kSource = LAPIS_SOURCE_DIR;
constexpr int kWidth = 900, kHeight = 700;

// Hair pixels: strand colours run from dark to light brown (red well above blue); skin and
// the bluish-grey background do not.
double hair_fraction(const viewer::Image& img) {
  size_t hair = 0;
  for (size_t k = 0; k < img.rgba.size(); k += 4) {
    const int r = img.rgba[k], b = img.rgba[k + 2];
    if (r > 25 && r > 1.6 * b + 10) ++hair;
  }
  return static_cast<double>(hair) / static_cast<double>(img.rgba.size() / 4);
}

// The app's first view: the orbit camera framed on the head's bounds.
geometry::CameraMatrices initial_camera(const hair_sketch::Head& head) {
  viewer::OrbitCamera cam;
  cam.frame(head.mesh.V.colwise().minCoeff().transpose(), head.mesh.V.colwise().maxCoeff().transpose());
  return cam.matrices(kWidth, kHeight);
}

// A visible scalp point on the right side of the head, a third of the way down the scalp's
// screen extent, in pixels: a downward drag from there runs down the side of the head.
Eigen::Vector2d scalp_pixel(const hair_sketch::Head& head, const geometry::CameraMatrices& cam) {
  const Eigen::Vector3d eye = geometry::eye_position(cam);
  std::vector<Eigen::Vector2d> visible;
  Eigen::Vector2d lo(1e9, 1e9), hi(-1e9, -1e9);
  for (Eigen::Index f = 0; f < head.mesh.F.rows(); ++f) {
    if (!head.scalp_face[static_cast<size_t>(f)]) continue;
    const Eigen::Vector3d c =
        (head.mesh.V.row(head.mesh.F(f, 0)) + head.mesh.V.row(head.mesh.F(f, 1)) + head.mesh.V.row(head.mesh.F(f, 2)))
            .transpose() /
        3.0;
    if (head.face_normals.row(f).dot((eye - c).normalized()) < 0.5) continue;  // clearly facing us
    const Eigen::Vector2d s = geometry::project(cam, c).head<2>();
    visible.push_back(s);
    lo = lo.cwiseMin(s), hi = hi.cwiseMax(s);
  }
  const Eigen::Vector2d target(0.5 * (lo.x() + hi.x()) + 0.3 * (hi.x() - lo.x()), lo.y() + 0.35 * (hi.y() - lo.y()));
  Eigen::Vector2d best(0, 0);
  for (const auto& s : visible)
    if ((s - target).norm() < (best - target).norm()) best = s;
  return best;
}

}  // namespace

TEST_CASE("apps: hair app — a stroke drawn with xdotool becomes a stream curve that follows the drag") {
  const fs::path dir = scratch_dir();
  const hair_sketch::Head head = hair_sketch::load_bundled_head(kSource);
  const geometry::CameraMatrices cam = initial_camera(head);
  const Eigen::Vector2d start = scalp_pixel(head, cam);
  REQUIRE(start.x() > 0);
  const fs::path session = dir / "drawn.json", shot = dir / "drawn.png", empty = dir / "empty.png",
                 events = dir / "drawn_events.json";
  // Without the gravity prior, so that an empty style has no hair (the prior's hair is checked last).
  const std::string size = " --size " + std::to_string(kWidth) + "x" + std::to_string(kHeight) + " --gravity-prior 0";
  REQUIRE(run_under_xvfb(kApp + size + " --headless --screenshot " + empty.string() + " --save-session " +
                         (dir / "unused.json").string()) == 0);

  // Drag downward from the scalp in small steps (a person's drag), save, screenshot, quit,
  // each step once the app says it handled the previous one and is idle: no fixed sleeps.
  std::string drag = "xdotool mousemove --window $w " + std::to_string(int(start.x())) + " " +
                     std::to_string(int(start.y())) + " mousedown 1";
  for (int k = 1; k <= 20; ++k)
    drag += " mousemove --window $w " + std::to_string(int(start.x() + 2 * k)) + " " +
            std::to_string(int(start.y() + 9 * k)) + " sleep 0.02";
  drag += " mouseup 1";
  const std::string body = kApp + size + " --save-session " + session.string() + " --screenshot " + shot.string() +
                           " --record " + events.string() + " --ready-file " + (dir / "drawn.ready").string() +
                           " &\napp=$!\n"
                           "window lapis-hair-sketch || { kill $app; exit 3; }\n"
                           "wait_ready '[ $busy -eq 0 ]' || { kill $app; exit 4; }\n"  // the first strands have grown
                           "mark; " +
                           drag +
                           "\n"
                           "wait_handled 0 2 || { kill $app; exit 5; }\n"  // press and release arrived, strands regrown
                           "mark; xdotool key --window $w ctrl+s; wait_handled 4 0 || { kill $app; exit 6; }\n"
                           "mark; xdotool key --window $w ctrl+p; wait_handled 4 0 || { kill $app; exit 7; }\n"
                           "xdotool key --window $w ctrl+q; wait $app\n";
  REQUIRE(run_under_xvfb(ready_script(dir / "drawn.sh", dir / "drawn.ready", body)) == 0);

  // The events arrived as sent: one press and one release of the left button, the moves between.
  const viewer::EventLog log = viewer::EventLog::load(events);
  int presses = 0, releases = 0, moves = 0;
  for (const auto& e : log.events) {
    if (e.type == viewer::EventType::MouseButton && e.button == 0) (e.action == 1 ? presses : releases)++;
    moves += e.type == viewer::EventType::MouseMove;
  }
  CHECK(presses == 1);
  CHECK(releases == 1);
  CHECK(moves >= 20);
  for (const auto& e : log.events)
    if (e.type == viewer::EventType::MouseButton && e.button == 0 && e.action == 1)
      // Where it was made, not where the pointer had got to when a loaded app read it.
      CHECK((Eigen::Vector2d(e.x, e.y) - Eigen::Vector2d(int(start.x()), int(start.y()))).norm() < 0.5);

  const hair_sketch::Hairstyle style = hair_sketch::load_session(session);
  REQUIRE(style.primitives.size() == 1);
  const auto* curve = std::get_if<hair_sketch::StreamCurve>(&style.primitives[0].shape);
  REQUIRE(curve != nullptr);
  REQUIRE(curve->points.size() >= 3);
  // On or above the scalp: no point inside the head.
  for (const auto& p : curve->points) CHECK(!head.inside(p));
  // The drag went down the screen: so does the curve.
  const Eigen::Vector3d a = geometry::project(cam, curve->points.front()),
                        b = geometry::project(cam, curve->points.back());
  CHECK(b.y() - a.y() > 60);
  CHECK(std::abs(b.x() - a.x()) < b.y() - a.y());
  // Resampled at d and lifted off the scalp.
  CHECK((a.head<2>() - start).norm() < 40);

  // Hair appeared where there was none.
  CHECK(hair_fraction(viewer::read_png(shot)) > hair_fraction(viewer::read_png(empty)) + 0.005);

  // A new style's default, the gravity prior, grows falling hair before any stroke.
  const fs::path prior = dir / "prior.png";
  REQUIRE(run_under_xvfb(kApp + " --size " + std::to_string(kWidth) + "x" + std::to_string(kHeight) +
                         " --headless --screenshot " + prior.string() + " --save-session " +
                         (dir / "prior.json").string()) == 0);
  MESSAGE("hair before any stroke: " << hair_fraction(viewer::read_png(prior)) << " with the prior, "
                                     << hair_fraction(viewer::read_png(empty)) << " without");
  CHECK(hair_fraction(viewer::read_png(prior)) > hair_fraction(viewer::read_png(empty)) + 0.02);
}

TEST_CASE("apps: hair app — replaying a recorded event file reproduces the recorded session") {
  const fs::path data = kSource / "tests/apps/data";
  const fs::path out = scratch_dir() / "replayed.json";
  REQUIRE(run_under_xvfb(kApp + " --headless --replay " + (data / "hair_stroke_events.json").string() +
                         " --exit-after-replay --save-session " + out.string()) == 0);
  const hair_sketch::Hairstyle replayed = hair_sketch::load_session(out);
  const hair_sketch::Hairstyle expected = hair_sketch::load_session(data / "hair_stroke_expected.json");
  REQUIRE(replayed.primitives.size() == expected.primitives.size());
  REQUIRE(!expected.primitives.empty());
  for (size_t i = 0; i < expected.primitives.size(); ++i)
    CHECK(hair_sketch::same_primitive(replayed.primitives[i], expected.primitives[i]));
  // Recorded with press positions taken from the events: each press lies where the pointer's
  // last move put it, not further along the drag (which made a stroke start late and jump back).
  const viewer::EventLog log = viewer::EventLog::load(data / "hair_stroke_events.json");
  Eigen::Vector2d pointer(-1, -1);
  int presses = 0;
  for (const auto& e : log.events) {
    if (e.type == viewer::EventType::MouseMove) pointer = {e.x, e.y};
    if (e.type == viewer::EventType::MouseButton && e.action == 1) {
      ++presses;
      CHECK((Eigen::Vector2d(e.x, e.y) - pointer).norm() == 0);
    }
  }
  CHECK(presses == 1);
}

namespace {

// Mean absolute difference per channel, in levels (0..255), of two pictures of one size.
double mean_difference(const viewer::Image& a, const viewer::Image& b) {
  REQUIRE(a.rgba.size() == b.rgba.size());
  double sum = 0;
  for (size_t k = 0; k < a.rgba.size(); k += 4)
    for (size_t c = 0; c < 3; ++c) sum += std::abs(static_cast<int>(a.rgba[k + c]) - static_cast<int>(b.rgba[k + c]));
  return sum / static_cast<double>(3 * a.rgba.size() / 4);
}

// Of the pixels where either picture shows something (not the background of its top left
// corner), the share that differ by more than `levels` in some channel.
double share_changed(const viewer::Image& a, const viewer::Image& b, int levels) {
  REQUIRE(a.rgba.size() == b.rgba.size());
  size_t covered = 0, changed = 0;
  for (size_t k = 0; k < a.rgba.size(); k += 4) {
    int from_background = 0, difference = 0;
    for (size_t c = 0; c < 3; ++c) {
      from_background =
          std::max({from_background, std::abs(a.rgba[k + c] - a.rgba[c]), std::abs(b.rgba[k + c] - b.rgba[c])});
      difference = std::max(difference, std::abs(a.rgba[k + c] - b.rgba[k + c]));
    }
    if (from_background <= 6) continue;
    ++covered;
    if (difference > levels) ++changed;
  }
  return covered ? static_cast<double>(changed) / static_cast<double>(covered) : 0.0;
}

}  // namespace

TEST_CASE("apps: hair app — every bundled session renders headless, as ribbons unlike plain lines") {
  int sessions = 0;
  for (const auto& entry : fs::directory_iterator(kSource / "assets/sessions")) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() != ".json" || name.find(".report.") != std::string::npos) continue;
    ++sessions;
    CAPTURE(entry.path().string());
    const std::string stem = entry.path().stem().string();
    const fs::path lines = scratch_dir() / (stem + "_lines.png"), ribbons = scratch_dir() / (stem + "_ribbons.png");
    const std::string common = kApp + " --session " + entry.path().string() + " --size 640x480 --supersample 2" +
                               " --save-session " + (scratch_dir() / "ignored.json").string();
    REQUIRE(run_under_xvfb(common + " --strands lines --render " + lines.string()) == 0);
    REQUIRE(run_under_xvfb(common + " --render " + ribbons.string()) == 0);
    const viewer::Image line_picture = viewer::read_png(lines), ribbon_picture = viewer::read_png(ribbons);
    CHECK(ribbon_picture.width == 640);
    CHECK(ribbon_picture.height == 480);
    const double hair_lines = hair_fraction(line_picture), hair_ribbons = hair_fraction(ribbon_picture);
    const double difference = mean_difference(line_picture, ribbon_picture);
    MESSAGE(name << ": hair-coloured " << hair_lines << " (lines), " << hair_ribbons << " (ribbons); mean difference "
                 << difference << " levels; of the pixels drawn, " << share_changed(line_picture, ribbon_picture, 8)
                 << " / " << share_changed(line_picture, ribbon_picture, 16) << " differ by > 8 / 16 levels");
    // Not blank: skin and background count as none. 2000 one-pixel strands combed off the face
    // cover 1.4% of an 800x600 view.
    CHECK(hair_lines > 0.01);
    CHECK(hair_ribbons > 0.01);
    CHECK(hair_ribbons < 0.7);  // not all hair
    // Ribbons taper, are shaded with two highlights and self-shadowed: a different picture
    // where there is hair.
    CHECK(share_changed(line_picture, ribbon_picture, 8) > 0.1);
  }
  CHECK(sessions >= 3);
}

TEST_CASE("apps: hair app — a render drawn in small tiles is the render drawn whole") {
  // Tiles restrict the projection to their part of the picture; a wrong restriction shifts,
  // stretches or seams the parts.
  const fs::path whole = scratch_dir() / "whole.png", tiled = scratch_dir() / "tiled.png";
  const std::string common = kApp + " --session " + (kSource / "assets/sessions/parting.json").string() +
                             " --size 500x380 --supersample 2 --save-session " +
                             (scratch_dir() / "ignored.json").string();
  REQUIRE(run_under_xvfb(common + " --render " + whole.string()) == 0);
  REQUIRE(run_under_xvfb(common + " --render-tile 97 --render " + tiled.string()) == 0);
  const viewer::Image a = viewer::read_png(whole), b = viewer::read_png(tiled);
  REQUIRE(a.width == b.width);
  size_t differing = 0;
  for (size_t k = 0; k < a.rgba.size(); k += 4)
    for (size_t c = 0; c < 3; ++c)
      if (std::abs(static_cast<int>(a.rgba[k + c]) - static_cast<int>(b.rgba[k + c])) > 24) {
        ++differing;
        break;
      }
  const double share = static_cast<double>(differing) / static_cast<double>(a.rgba.size() / 4);
  MESSAGE("mean difference " << mean_difference(a, b) << " levels; " << share << " of the pixels differ by > 24");
  CHECK(mean_difference(a, b) < 0.5);
  CHECK(share < 0.002);
}

TEST_CASE("apps: hair app — a headless export that cannot be written fails the run, naming the cause") {
  const fs::path dir = scratch_dir();
  std::ofstream(dir / "a_file") << "not a directory";
  const fs::path log = dir / "export_failed.log";
  const int status =
      run_under_xvfb("timeout 300 " + kApp + " --headless --size 320x240 --export-hair " +
                     (dir / "a_file" / "s.hair").string() + " --export-obj " + (dir / "a_file" / "s.obj").string() +
                     " --save-session " + (dir / "a_file" / "s.json").string() + " > " + log.string() + " 2>&1");
  std::ifstream in(log);
  const std::string output((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CAPTURE(output);
  CHECK(status == 1);  // not 0 (the export failed) and not an abort (134: uncaught filesystem_error)
  CHECK(output.find("export failed: core::create_parent_directories(): ") != std::string::npos);
  CHECK(output.find("exported") == std::string::npos);
  // The autosave beside --save-session F/s.json, F a file, is reported, not an abort.
  CHECK(output.find("autosave on exit failed: core::create_parent_directories(): ") != std::string::npos);
}

TEST_CASE("apps: hair app — a cut line drawn with xdotool (tool 7) ends the strands it crosses") {
  const fs::path dir = scratch_dir();
  hair_sketch::Hairstyle start = hair_sketch::load_session(kSource / "assets/sessions/smooth.json");
  start.settings.head_mesh = (kSource / "assets/head.obj").string();
  start.settings.scalp_mask = (kSource / "assets/head_scalp.txt").string();
  const fs::path session = dir / "cut.json";
  hair_sketch::save_session(session, start);
  // Across the hair, clear of the panels (Hair at the bottom left, the column on the right).
  const int y = 330, x0 = 200, x1 = 540;
  std::string drag = "xdotool mousemove --window $w " + std::to_string(x0) + " " + std::to_string(y) + " mousedown 1";
  for (int x = x0 + 20; x <= x1; x += 20)
    drag += " mousemove --window $w " + std::to_string(x) + " " + std::to_string(y) + " sleep 0.02";
  drag += " mouseup 1";
  const std::string size = " --size " + std::to_string(kWidth) + "x" + std::to_string(kHeight);
  const std::string body = kApp + size + " --session " + session.string() + " --ready-file " +
                           (dir / "cut.ready").string() +
                           " &\napp=$!\n"
                           "window lapis-hair-sketch || { kill $app; exit 3; }\n"
                           "wait_ready '[ $busy -eq 0 ]' || { kill $app; exit 4; }\n"
                           "mark; xdotool key --window $w 7; wait_handled 2 0 || { kill $app; exit 5; }\n"
                           "mark; " +
                           drag +
                           "\nwait_handled 0 2 || { kill $app; exit 6; }\n"
                           "mark; xdotool key --window $w ctrl+s; wait_handled 4 0 || { kill $app; exit 7; }\n"
                           "xdotool key --window $w ctrl+q; wait $app\n";
  REQUIRE(run_under_xvfb(ready_script(dir / "cut.sh", dir / "cut.ready", body)) == 0);

  const hair_sketch::Hairstyle style = hair_sketch::load_session(session);
  REQUIRE(style.details.size() == 1);
  const auto* cut = std::get_if<hair_sketch::CutDetail>(&style.details[0].shape);
  REQUIRE(cut != nullptr);
  CHECK((cut->line.front() - Eigen::Vector2d(x0, y)).norm() < 0.5);
  CHECK((cut->line.back() - Eigen::Vector2d(x1, y)).norm() < 0.5);

  // Segments that cross the drawn line downward, seen with the camera it was drawn with.
  const hair_sketch::Head head = hair_sketch::load_session_head(style, session);
  const auto crossings = [&](const hair_sketch::Strands& s) {
    int n = 0;
    for (int i = 0; i < s.count(); ++i)
      for (int k = s.offsets[i] + 1; k < s.offsets[i + 1]; ++k) {
        const Eigen::Vector3d a = geometry::project(cut->camera, s.points[k - 1].cast<double>()),
                              b = geometry::project(cut->camera, s.points[k].cast<double>());
        n += a.x() > x0 + 1 && a.x() < x1 - 1 && a.y() < y - 0.5 && b.y() > y + 0.5;
      }
    return n;
  };
  hair_sketch::Hairstyle uncut = style;
  uncut.details.clear();
  const int before = crossings(hair_sketch::build_hairstyle(uncut, head).strands);
  const int after = crossings(hair_sketch::build_hairstyle(style, head).strands);
  MESSAGE("segments crossing the cut line: " << before << " without the cut, " << after << " with it");
  CHECK(before > 100);
  CHECK(after == 0);
}

TEST_CASE("apps: hair app — an edit shows the strands on screen first, then grows the rest behind them") {
  // Two downward strokes from the top of the head in the first view, each waiting for the
  // last one's strands. The window draws every k-th strand (a pinned budget of 20K segments of
  // 20K strands): each edit must show those first and keep that picture when the rest arrive.
  nlohmann::json events = {{"format", "lapis-events"}, {"version", 1}, {"width", kWidth}, {"height", kHeight}};
  int frame = 10;
  for (const auto& [x0, y0] : {std::pair{506, 187}, std::pair{450, 175}}) {
    events["events"].push_back({{"type", "move"}, {"frame", frame}, {"x", x0}, {"y", y0}});
    events["events"].push_back(
        {{"type", "button"}, {"frame", frame + 1}, {"x", x0}, {"y", y0}, {"button", 0}, {"action", 1}, {"mods", 0}});
    for (int i = 1; i <= 18; ++i)
      events["events"].push_back(
          {{"type", "move"}, {"frame", frame + 1 + i / 2}, {"x", x0 + 2 * i}, {"y", y0 + 9 * i}});
    events["events"].push_back({{"type", "button"},
                                {"frame", frame + 11},
                                {"x", x0 + 36},
                                {"y", y0 + 162},
                                {"button", 0},
                                {"action", 0},
                                {"mods", 0}});
    events["events"].push_back({{"type", "idle"}, {"frame", frame + 12}});
    frame += 20;
  }
  const fs::path replay = scratch_dir() / "preview_events.json", report = scratch_dir() / "preview_benchmark.json";
  std::ofstream(replay) << events.dump();
  REQUIRE(run_under_xvfb(kApp + " --roots 20000 --draw-segments 20000 --size 900x700 --replay " + replay.string() +
                         " --exit-after-replay --benchmark " + report.string()) == 0);
  nlohmann::json r;
  std::ifstream(report) >> r;
  REQUIRE(r["edits"].size() == 2);
  for (const auto& e : r["edits"]) {
    CHECK(e["preview"].get<bool>());
    CHECK_FALSE(e["redrawn"].get<bool>());
    // The preview grew a thirtieth of the strands; the rest came after the frame.
    CHECK(e["rest_ms"].get<double>() > e["growth_ms"].get<double>());
    CHECK(e["all_strands_ms"].get<double>() > e["total_ms"].get<double>() - e["draw_ms"].get<double>());
  }
  CHECK(r["strands"].get<int>() > 15000);  // every strand arrived in the end
}
