// The merge app, for real: driven by xdotool under Xvfb (pair two loops, set a key, merge,
// export; move the source with the gizmo; paint and cut a closed source; a dependent merge with
// a handle), replayed from the committed recording of such a session (also with undo / redo),
// and rendered headless. The exports must be watertight where the paired loops were and equal
// `lapis merge` on the exported files; bad input must come back as the module's messages.
#include <doctest/doctest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "app_runner.h"
#include "first_view.h"  // lapis-merge's camera angles and panel width
#include "lapis/geometry/bvh.h"
#include "lapis/geometry/connectivity.h"
#include "lapis/geometry/dijkstra.h"
#include "lapis/geometry/io.h"
#include "lapis/geometry/procedural.h"
#include "lapis/mesh_merge/merge_setup.h"
#include "lapis/mesh_merge/pairs_file.h"
#include "lapis/mesh_merge/suggest_key.h"
#include "lapis/viewer/gizmo.h"
#include "lapis/viewer/loop_picking.h"
#include "lapis/viewer/orbit_camera.h"
#include "merge_app.h"  // remerge_ms

using namespace lapis;
using namespace lapis::apps_test;

namespace {

const std::string kApp = LAPIS_MERGE_APP_EXE;
const std::string kCli = LAPIS_CLI_EXE;
const fs::path kSource = LAPIS_SOURCE_DIR;
constexpr int kWidth = 1000, kHeight = 700;
const std::string kSize = " --size " + std::to_string(kWidth) + "x" + std::to_string(kHeight);

geometry::TriMesh asset(const std::string& name) { return geometry::read_mesh(kSource / "assets/merge" / name); }

// The app's first view of the default preset (dome onto neck, the dome placed beside the neck's
// rim): the camera of MergeApp::on_start() framed on both meshes.
geometry::CameraMatrices first_view(const geometry::TriMesh& source, const geometry::TriMesh& target) {
  return merge_app::first_view_camera(source, target, kWidth, kHeight).matrices(kWidth, kHeight);
}

std::string pixel(const Eigen::Vector3d& s) {
  return std::to_string(std::lround(s.x())) + " " + std::to_string(std::lround(s.y()));
}

// A shell script that starts the app under xdotool with `flags`, waits until it has drawn and
// is idle (--ready-file), runs `actions` ($w is its window) and quits it.
std::string xdotool_session(const std::string& flags, const std::string& actions) {
  const fs::path dir = scratch_dir();
  return ready_script(dir / "merge.sh", dir / "merge.ready",
                      kApp + kSize + " " + flags + " --ready-file " + (dir / "merge.ready").string() +
                          " &\napp=$!\nwindow lapis-merge || { kill $app; exit 3; }\n"
                          "wait_ready '[ $busy -eq 0 ]' || { kill $app; exit 4; }\n" +
                          actions + "\nxdotool key --window $w ctrl+q; wait $app\n");
}

std::string text_of(const fs::path& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

std::string click(const Eigen::Vector2i& p) {
  return "mark; xdotool mousemove --window $w " + std::to_string(p.x()) + " " + std::to_string(p.y()) +
         " sleep 0.1 click 1; wait_handled 0 2 || { kill $app; exit 5; }\n";
}

// Tool 1 picks a loop on each side, then (the app switches to tool 2) a vertex on each.
std::string pair_and_key_clicks(const Eigen::Vector2i& s, const Eigen::Vector2i& t) {
  return click(s) + click(t) + click(s) + click(t);
}

struct DefaultScene {
  geometry::TriMesh source, target;
  geometry::CameraMatrices camera;
  std::vector<int> sloop, tloop;  // the dome's rim and the neck rim facing it
  DefaultScene() : target(asset("neck.obj")) {
    const geometry::TriMesh dome = asset("dome.obj");
    mesh_merge::MergeSetup s;
    s.source = std::make_shared<const geometry::TriMesh>(dome);
    s.placement = mesh_merge::suggest_placement(dome, target);
    source = mesh_merge::placed_source(s);
    camera = first_view(source, target);
    const geometry::Connectivity sc(source), tc(target);
    sloop = sc.boundary_loops().at(0);
    tloop = tc.boundary_loops().at(
        static_cast<size_t>(mesh_merge::facing_target_loop(source, sloop, target, tc.boundary_loops())));
  }
  std::string pair_and_key() const {
    return pair_and_key_clicks(front_pixel(source, sloop), front_pixel(target, tloop));
  }
  // A handle far from the rim: the source vertex nearest the eye among the upper half (in z)
  // of the dome.
  int far_handle() const {
    double zmin = 1e300, zmax = -1e300;
    for (int v = 0; v < source.num_vertices(); ++v)
      zmin = std::min(zmin, source.V(v, 2)), zmax = std::max(zmax, source.V(v, 2));
    const Eigen::Vector3d eye = geometry::eye_position(camera);
    int handle = -1;
    for (int v = 0; v < source.num_vertices(); ++v)
      if (source.V(v, 2) > 0.5 * (zmin + zmax) &&
          (handle < 0 || (source.V.row(v).transpose() - eye).norm() < (source.V.row(handle).transpose() - eye).norm()))
        handle = v;
    return handle;
  }
  // The dome's top: the vertex farthest from its rim along the surface.
  int apex() const {
    const geometry::ShortestPaths d = geometry::dijkstra(source, sloop);
    return static_cast<int>(std::max_element(d.distance.begin(), d.distance.end()) - d.distance.begin());
  }
  // Tool 3, then a click on source vertex v.
  std::string click_handle(int v) const {
    const Eigen::Vector3d h = geometry::project(camera, source.V.row(v).transpose());
    return "mark; xdotool key --window $w 3; wait_handled 2 0; mark; xdotool mousemove --window $w " + pixel(h) +
           " sleep 0.1 click 1; wait_handled 0 2; ";
  }
  // The pixel of the loop vertex nearest the eye (in front, so visible) of `loop`.
  Eigen::Vector2i front_pixel(const geometry::TriMesh& m, const std::vector<int>& loop) const {
    const Eigen::Vector3d eye = geometry::eye_position(camera);
    int best = loop[0];
    for (int v : loop)
      if ((m.V.row(v).transpose() - eye).norm() < (m.V.row(best).transpose() - eye).norm()) best = v;
    const Eigen::Vector3d s = geometry::project(camera, m.V.row(best).transpose());
    return {static_cast<int>(std::lround(s.x())), static_cast<int>(std::lround(s.y()))};
  }
};

constexpr int kM = 77, kT = 84;  // GLFW key codes: merge, transition regions

// tests/apps/data/merge_events.json (pair two loops, set a key, merge) followed by presses of
// the given (key, modifiers), 20 frames apart, written to `path`.
void write_recorded_session_then_keys(const fs::path& path, const std::vector<std::pair<int, int>>& keys) {
  nlohmann::json j = nlohmann::json::parse(text_of(kSource / "tests/apps/data/merge_events.json"));
  long frame = j["events"].back()["frame"].get<long>();
  for (const auto& [key, mods] : keys) {
    frame += 20;
    j["events"].push_back({{"type", "key"}, {"frame", frame}, {"key", key}, {"action", 1}, {"mods", mods}});
    j["events"].push_back({{"type", "key"}, {"frame", frame + 1}, {"key", key}, {"action", 0}, {"mods", mods}});
  }
  std::ofstream(path) << j.dump();
}

// An event log with one key press: M (merge) at frame 5.
void write_merge_key_events(const fs::path& path) {
  std::ofstream out(path);
  out << R"({"format": "lapis-events", "version": 1, "width": 800, "height": 600, "events": [)"
      << R"({"type": "key", "frame": 5, "key": 77, "action": 1, "mods": 0},)"
      << R"({"type": "key", "frame": 6, "key": 77, "action": 0, "mods": 0}]})";
}

struct Exported {
  geometry::TriMesh merged, source, target;
  std::vector<mesh_merge::LoopPair> pairs;
  std::string command;
};

Exported read_exports(const fs::path& prefix) {
  Exported e;
  const std::string p = prefix.string();
  e.merged = geometry::read_mesh(p + ".obj");
  e.source = geometry::read_mesh(p + "_source.obj");
  e.target = geometry::read_mesh(p + "_target.obj");
  e.pairs = mesh_merge::read_pairs_file(p + "_pairs.json");
  std::ifstream in(p + "_command.txt");
  std::getline(in, e.command);
  return e;
}

// Watertight where the paired loops were: the merged mesh's boundary is exactly the target's
// unpaired loops (target vertices away from the seam never move), nothing of the paired ones.
void check_watertight_seam(const Exported& e) {
  const geometry::Connectivity tc(e.target), mc(e.merged), sc(e.source);
  std::set<int> paired_target_loops;
  for (const auto& p : e.pairs)
    for (size_t l = 0; l < tc.boundary_loops().size(); ++l) {
      const auto& loop = tc.boundary_loops()[l];
      if (std::find(loop.begin(), loop.end(), p.keys.at(0).target) != loop.end())
        paired_target_loops.insert(static_cast<int>(l));
    }
  REQUIRE(paired_target_loops.size() == e.pairs.size());
  std::set<std::array<double, 3>> kept;
  for (size_t l = 0; l < tc.boundary_loops().size(); ++l)
    if (!paired_target_loops.count(static_cast<int>(l)))
      for (int v : tc.boundary_loops()[l]) kept.insert({e.target.V(v, 0), e.target.V(v, 1), e.target.V(v, 2)});
  const size_t expected_loops = tc.boundary_loops().size() + sc.boundary_loops().size() - 2 * e.pairs.size();
  CHECK(mc.boundary_loops().size() == expected_loops);
  size_t boundary_vertices = 0;
  for (const auto& loop : mc.boundary_loops())
    for (int v : loop) {
      ++boundary_vertices;
      CHECK(kept.count({e.merged.V(v, 0), e.merged.V(v, 1), e.merged.V(v, 2)}) == 1);
    }
  CHECK(boundary_vertices == kept.size());
  CHECK(geometry::validate(e.merged).ok());
}

// The export's one handle: the merged mesh has a vertex at its placed position, bit for bit.
void check_one_handle_kept(const Exported& e, const fs::path& prefix) {
  const std::vector<int> handles = mesh_merge::read_handles_file(prefix.string() + "_handles.json");
  REQUIRE(handles.size() == 1);
  bool kept = false;
  for (int v = 0; v < e.merged.num_vertices() && !kept; ++v) kept = e.merged.V.row(v) == e.source.V.row(handles[0]);
  CHECK(kept);
}

// Runs the exported `lapis merge` command with another --out and compares (1e-9).
void check_equals_cli(const Exported& e, const fs::path& out) {
  REQUIRE(e.command.rfind("lapis merge ", 0) == 0);
  std::istringstream words(e.command.substr(6));
  std::string cmd = kCli, w;
  while (words >> w) {
    if (w == "--out") {
      words >> w;
      w = out.string();
      cmd += " --out";
    }
    cmd += " " + w;
  }
  REQUIRE_MESSAGE(run(cmd + " > /dev/null") == 0, cmd);
  const geometry::TriMesh cli = geometry::read_mesh(out);
  REQUIRE(cli.F == e.merged.F);
  CHECK((cli.V - e.merged.V).cwiseAbs().maxCoeff() <= 1e-9);
}

}  // namespace

TEST_CASE("apps: merge app — pairing two loops and a key with xdotool, then merge and export") {
  const fs::path dir = scratch_dir();
  const DefaultScene scene;
  const auto& sloop = scene.sloop;
  const auto& tloop = scene.tloop;
  const Eigen::Vector2i s = scene.front_pixel(scene.source, sloop), t = scene.front_pixel(scene.target, tloop);
  // Clear of the panels on the right and the menu bar.
  REQUIRE(s.x() > 0);
  REQUIRE(s.x() < kWidth - merge_app::kPanelWidth);
  REQUIRE(t.x() < kWidth - merge_app::kPanelWidth);
  REQUIRE(std::min(s.y(), t.y()) > 30);
  const fs::path events = dir / "merge_events.json", prefix = dir / "live";
  REQUIRE(run_under_xvfb(xdotool_session("--record " + events.string() + " --export " + prefix.string(),
                                         pair_and_key_clicks(s, t) +
                                             "mark; xdotool key --window $w m; wait_handled 2 0;"
                                             " mark; xdotool key --window $w ctrl+e; wait_handled 4 0;")) == 0);
  const Exported e = read_exports(prefix);
  REQUIRE(e.pairs.size() == 1);
  REQUIRE(e.pairs[0].keys.size() == 1);
  // The key joins the two clicked loops.
  CHECK(std::find(sloop.begin(), sloop.end(), e.pairs[0].keys[0].source) != sloop.end());
  CHECK(std::find(tloop.begin(), tloop.end(), e.pairs[0].keys[0].target) != tloop.end());
  check_watertight_seam(e);
  check_equals_cli(e, dir / "live_cli.obj");
}

// Keys act on the view while the pointer is over it. With the merge panel focused (a click on it),
// ImGui's tabbing once took Tab typed over the view to the "smoothing iterations" field, and the
// 5 typed next went into it instead of picking the paint tool.
TEST_CASE("apps: merge app — keys typed over the view reach the app, not a field of the focused panel") {
  const fs::path dir = scratch_dir();
  const DefaultScene scene;
  const fs::path prefix = dir / "keys";
  const std::string keys =
      "mark; xdotool mousemove --window $w 950 150 sleep 0.1 click 1; wait_handled 0 2 || { kill $app; exit 5; }\n"
      "xdotool mousemove --window $w 100 600; mark; xdotool key --window $w Tab; wait_handled 2 0;"
      " mark; xdotool key --window $w 5; wait_handled 2 0; mark; xdotool key --window $w Return; wait_handled 2 0;"
      " mark; xdotool key --window $w Tab; wait_handled 2 0; mark; xdotool key --window $w 1; wait_handled 2 0;\n";
  REQUIRE(run_under_xvfb(xdotool_session("--export " + prefix.string(),
                                         keys + scene.pair_and_key() +
                                             "mark; xdotool key --window $w m; wait_handled 2 0;"
                                             " mark; xdotool key --window $w ctrl+e; wait_handled 4 0;")) == 0);
  const Exported e = read_exports(prefix);
  CHECK_MESSAGE(e.command.find("--smooth 3") != std::string::npos, e.command);
  REQUIRE(e.pairs.size() == 1);
  check_watertight_seam(e);
}

// Loops are drawn on top of the surfaces, so a click on any drawn point of one picks it, hidden
// or not, and a click that misses keeps the half-made pair: the target loop, a miss, then the
// dome's rim where the dome hides it, pair the two.
TEST_CASE("apps: merge app — a loop is picked where it is drawn, hidden or not, and a miss keeps the half-made pair") {
  const fs::path dir = scratch_dir(), prefix = dir / "hidden";
  const DefaultScene scene;
  const geometry::Bvh source_bvh(scene.source), target_bvh(scene.target);
  auto pixel_of = [&](const Eigen::Vector3d& P) { return geometry::project(scene.camera, P).head<2>().eval(); };
  // A point of the source loop that the surfaces hide, inside the view, 30 px from every drawn
  // point of the target's loops.
  Eigen::Vector2i hidden(-1, -1);
  const geometry::Connectivity tc(scene.target);
  for (size_t i = 0; i < scene.sloop.size() && hidden.x() < 0; ++i) {
    const Eigen::Vector3d P = scene.source.V.row(scene.sloop[i]).transpose();
    const Eigen::Vector2d q = pixel_of(P);
    if (viewer::visible(scene.camera, P, {&source_bvh, &target_bvh})) continue;
    if (q.x() < 40 || q.x() > kWidth - merge_app::kPanelWidth - 40 || q.y() < 100 || q.y() > kHeight - 40) continue;
    bool near_target = false;
    for (const auto& loop : tc.boundary_loops())
      for (int v : loop) near_target = near_target || (pixel_of(scene.target.V.row(v).transpose()) - q).norm() < 30;
    if (!near_target) hidden = {static_cast<int>(std::lround(q.x())), static_cast<int>(std::lround(q.y()))};
  }
  REQUIRE(hidden.x() >= 0);
  const Eigen::Vector2i s = scene.front_pixel(scene.source, scene.sloop),
                        t = scene.front_pixel(scene.target, scene.tloop);
  const std::string actions = click(t) + click({60, kHeight - 60}) + click(hidden) + click(s) + click(t) +
                              "mark; xdotool key --window $w m; wait_handled 2 0;"
                              " mark; xdotool key --window $w ctrl+e; wait_handled 4 0;";
  REQUIRE(run_under_xvfb(xdotool_session("--export " + prefix.string(), actions)) == 0);
  const Exported e = read_exports(prefix);
  REQUIRE(e.pairs.size() == 1);
  CHECK(e.pairs[0].keys.size() == 1);
  check_watertight_seam(e);
}

// Auto-merge pauses when a merge of the next edit would be slow. The first merge of a setup
// pays the Merger's one-off precompute, which the next edit of pairs, keys or smoothing reuses:
// a 0.9 s first merge with 0.75 s of precompute keeps auto-merge on; a slow re-merge pauses it.
TEST_CASE("apps: merge app — auto-merge judges by the re-merge time, not by the first merge's precompute") {
  merge_app::MergeOutcome first;
  first.job_ms = 900, first.precompute_ms = 750, first.reused = false;
  CHECK(merge_app::remerge_ms(first) == doctest::Approx(150));
  CHECK(merge_app::remerge_ms(first) < merge_app::kAutoMergeMs);
  merge_app::MergeOutcome slow = first;
  slow.reused = true;  // the precompute was an earlier job's: all 0.9 s are the re-merge
  CHECK(merge_app::remerge_ms(slow) == doctest::Approx(900));
  CHECK(merge_app::remerge_ms(slow) >= merge_app::kAutoMergeMs);
}

// Pixels of the 3D view (left of the panels, below the overlay) shaded in the source's warm
// colour and in the target's cool one.
std::pair<long, long> warm_and_cool_pixels(const viewer::Image& im) {
  long warm = 0, cool = 0;
  for (int y = 80; y < im.height; ++y)
    for (int x = 0; x < im.width - merge_app::kPanelWidth - 10; ++x) {
      const std::uint8_t* p = &im.rgba[4 * (static_cast<size_t>(y) * im.width + x)];
      warm += p[0] > p[2] + 40;
      cool += p[2] > p[0] + 15;
    }
  return {warm, cool};
}

// File > Open source places the opened mesh beside the target at its size: the lion's head,
// ten times the neck's size as stored, once filled the view with the neck a speck beside it.
TEST_CASE("apps: merge app — a source opened from the menu arrives beside the target at its size") {
  const fs::path dir = scratch_dir(), shot = dir / "opened.png";
  const DefaultScene scene;
  const std::string open_lion =
      "mark; xdotool mousemove --window $w 662 38 sleep 0.1 click 1; wait_handled 0 2 || { kill $app; exit 5; }\n"
      "xdotool mousemove --window $w 680 80 sleep 0.3 mousemove --window $w 500 80 sleep 0.3 mousemove --window $w 500 "
      "249 sleep 0.3; mark; xdotool click 1; wait_handled 0 2 || { kill $app; exit 6; }\n";
  REQUIRE(run_under_xvfb(xdotool_session("--screenshot " + shot.string(),
                                         scene.pair_and_key() + "mark; xdotool key --window $w m; wait_handled 2 0;\n" +
                                             open_lion + "mark; xdotool key --window $w ctrl+p; wait_handled 2 0;")) ==
          0);
  REQUIRE(fs::exists(shot));
  const auto [warm, cool] = warm_and_cool_pixels(viewer::read_png(shot));
  MESSAGE("source pixels " << warm << ", target pixels " << cool);
  CHECK(warm > 2000);
  CHECK(cool > 0.25 * warm);
}

TEST_CASE("apps: merge app — replaying the recorded pairing session merges watertight and equals lapis merge") {
  const fs::path dir = scratch_dir(), prefix = dir / "replayed";
  REQUIRE(run_under_xvfb(kApp + " --headless --replay " + (kSource / "tests/apps/data/merge_events.json").string() +
                         " --exit-after-replay --export " + prefix.string()) == 0);
  const Exported e = read_exports(prefix);
  REQUIRE(e.pairs.size() == 1);
  REQUIRE(e.pairs[0].keys.size() == 1);
  check_watertight_seam(e);
  check_equals_cli(e, dir / "replayed_cli.obj");
}

TEST_CASE("apps: merge app — a headless export that cannot be written, or has no merge, fails the run") {
  const fs::path dir = scratch_dir();
  std::ofstream(dir / "a_file") << "not a directory";
  const fs::path log = dir / "export_failed.log";
  CHECK(run_under_xvfb(kApp + " --headless --replay " + (kSource / "tests/apps/data/merge_events.json").string() +
                       " --exit-after-replay --export " + (dir / "a_file" / "m").string() + " > " + log.string() +
                       " 2>&1") == 1);
  std::string output = text_of(log);
  CAPTURE(output);
  CHECK(output.find("lapis-merge: export failed: ") != std::string::npos);
  CHECK(output.find("exported") == std::string::npos);
  // Nothing paired: the merge fails, and so does the export the run asked for.
  CHECK(run_under_xvfb(kApp + " --headless --export " + (dir / "unpaired").string() + " > " + log.string() + " 2>&1") ==
        1);
  output = text_of(log);
  CHECK(output.find("lapis-merge: export: nothing to export, the merge failed: ") != std::string::npos);
  CHECK(!fs::exists(dir / "unpaired.obj"));
}

TEST_CASE("apps: merge app — the headless screenshot after a merge is neither blank nor the unedited scene") {
  const fs::path dir = scratch_dir(), before = dir / "before.png", after = dir / "after.png";
  REQUIRE(run_under_xvfb(kApp + kSize + " --headless --screenshot " + before.string()) == 0);
  REQUIRE(run_under_xvfb(kApp + " --headless --replay " + (kSource / "tests/apps/data/merge_events.json").string() +
                         " --screenshot " + after.string()) == 0);
  const viewer::Image a = viewer::read_png(before), b = viewer::read_png(after);
  REQUIRE(a.width == b.width);
  REQUIRE(a.height == b.height);
  CHECK(foreground_fraction(a) > 0.03);
  CHECK(foreground_fraction(b) > 0.03);
  size_t differ = 0;
  for (size_t k = 0; k < a.rgba.size(); k += 4)
    if (std::abs(a.rgba[k] - b.rgba[k]) + std::abs(a.rgba[k + 1] - b.rgba[k + 1]) +
            std::abs(a.rgba[k + 2] - b.rgba[k + 2]) >
        30)
      ++differ;
  CHECK(static_cast<double>(differ) / static_cast<double>(a.rgba.size() / 4) > 0.01);
}

TEST_CASE("apps: merge app — merging before anything is paired reports the module's error and keeps running") {
  const fs::path dir = scratch_dir(), events = dir / "merge_now.json", log = dir / "merge_now.log";
  write_merge_key_events(events);
  REQUIRE(run_under_xvfb(kApp + " --headless --replay " + events.string() + " --exit-after-replay 2> " +
                         log.string()) == 0);
  const std::string text = text_of(log);
  CHECK(text.find("merge failed: mesh_merge::check_merge_input(): 0 loop pairs for a source with 1 boundary loops") !=
        std::string::npos);
}

TEST_CASE("apps: merge app — the gizmo moves the source along the dragged axis; the merge still equals lapis merge") {
  const fs::path dir = scratch_dir(), prefix = dir / "moved";
  const DefaultScene scene;
  // The gizmo sits on the placed source's centroid; grab its y arrow near the tip (beyond the
  // rings) and drag it 60 pixels up the screen (world y is the screen's up).
  viewer::Gizmo gizmo;
  const Eigen::Vector3d c = scene.source.V.colwise().mean().transpose();
  gizmo.set_center(c);
  const Eigen::Vector3d grab =
      geometry::project(scene.camera, c + 0.9 * gizmo.world_size(scene.camera) * Eigen::Vector3d::UnitY());
  REQUIRE(gizmo.hit(scene.camera, grab.head<2>()) == viewer::GizmoPart::TranslateY);
  std::string drag =
      "mark; xdotool key --window $w 4; wait_handled 2 0 || { kill $app; exit 5; }\nmark; xdotool mousemove --window "
      "$w " +
      pixel(grab) + " sleep 0.1 mousedown 1";
  for (int k = 1; k <= 12; ++k)
    drag += " mousemove --window $w " + std::to_string(std::lround(grab.x())) + " " +
            std::to_string(std::lround(grab.y()) - 5 * k) + " sleep 0.05";
  drag += " mouseup 1; wait_handled 0 2 || { kill $app; exit 5; }\n";
  REQUIRE(run_under_xvfb(xdotool_session(
              "--export " + prefix.string(),
              scene.pair_and_key() + drag + "mark; xdotool key --window $w m; wait_handled 2 0;")) == 0);
  const Exported e = read_exports(prefix);
  REQUIRE(e.source.num_vertices() == scene.source.num_vertices());
  // A pure translation along +y: every vertex moved by the same vector.
  const Eigen::RowVector3d d = e.source.V.row(0) - scene.source.V.row(0);
  CHECK(d.y() > 0.05);
  CHECK(std::abs(d.x()) < 1e-9);
  CHECK(std::abs(d.z()) < 1e-9);
  CHECK(((e.source.V - scene.source.V).rowwise() - d).cwiseAbs().maxCoeff() < 1e-9);
  check_watertight_seam(e);
  check_equals_cli(e, dir / "moved_cli.obj");
}

TEST_CASE("apps: merge app — painting a region on a closed source and cutting gives it an open rim") {
  // The cactus is closed: merging it says so. Painted across its middle and cut, it has one
  // boundary loop, so the module's complaint becomes the missing pair.
  const fs::path dir = scratch_dir(), log = dir / "paint.log";
  const fs::path cactus = kSource / "assets/external/cactus.off",
                 other = kSource / "assets/merge/dome_placed.obj";  // beside the cactus, not around it
  REQUIRE_MESSAGE(fs::exists(cactus), "run scripts/setup");
  const geometry::TriMesh source = geometry::read_mesh(cactus), target = geometry::read_mesh(other);
  const geometry::CameraMatrices cam = first_view(source, target);
  const Eigen::Vector3d mid = geometry::project(cam, source.V.colwise().mean().transpose());
  std::string paint =
      "mark; xdotool key --window $w m; wait_handled 2 0; mark; xdotool key --window $w 5; wait_handled 2 0; mark; "
      "xdotool mousemove --window $w " +
      std::to_string(std::lround(mid.x()) - 20) + " " + std::to_string(std::lround(mid.y())) + " sleep 0.1 mousedown 1";
  for (int k = 1; k <= 8; ++k)
    paint += " mousemove --window $w " + std::to_string(std::lround(mid.x()) - 20 + 5 * k) + " " +
             std::to_string(std::lround(mid.y())) + " sleep 0.05";
  paint +=
      " mouseup 1; wait_handled 0 2; mark; xdotool key --window $w c; wait_handled 2 0; mark; xdotool key --window $w "
      "m; "
      "wait_handled 2 0;";
  REQUIRE(run_under_xvfb(xdotool_session("--source " + cactus.string() + " --target " + other.string(), paint) +
                         " 2> " + log.string()) == 0);
  const std::string text = text_of(log);
  CHECK(text.find("merge failed: mesh_merge::check_merge_input(): the source is closed (no boundary loop)") !=
        std::string::npos);
  CHECK(text.find("merge failed: mesh_merge::check_merge_input(): 0 loop pairs for a source with 1 boundary loops") !=
        std::string::npos);
  CHECK(text.find("not manifold") == std::string::npos);
}

// A stroke across the whole width of the cactus's trunk, cut: the plain brush paints its front,
// so the source keeps a half-shell patch; the x-ray brush paints it all round, so the cut runs
// round the trunk and the source keeps everything above it (the region's one rim, the part
// beyond it filled in as cut_by_region() does).
TEST_CASE("apps: merge app — paint & cut with x-ray cuts all round the trunk, not a half-shell") {
  const fs::path dir = scratch_dir();
  const fs::path cactus = kSource / "assets/external/cactus.off", other = dir / "speck.obj";
  REQUIRE_MESSAGE(fs::exists(cactus), "run scripts/setup");
  const geometry::TriMesh source = geometry::read_mesh(cactus);
  // The target: a speck inside the cactus, so the first view frames the cactus alone, large.
  geometry::TriMesh target = geometry::make_icosphere(1, 1e-3);
  target.V.rowwise() += 0.5 * (source.V.colwise().minCoeff() + source.V.colwise().maxCoeff());
  geometry::write_mesh(other, target);
  const geometry::CameraMatrices cam = first_view(source, target);
  const Eigen::Vector3d mid = geometry::project(cam, source.V.colwise().mean().transpose());
  double left = 1e9, right = -1e9;  // the trunk's width on screen at the stroke's height
  for (int v = 0; v < source.num_vertices(); ++v) {
    const Eigen::Vector3d p = geometry::project(cam, source.V.row(v).transpose());
    if (std::abs(p.y() - mid.y()) < 3 && std::abs(p.x() - mid.x()) < 250)
      left = std::min(left, p.x()), right = std::max(right, p.x());
  }
  REQUIRE(right - left > 10);
  auto cut_log = [&](bool xray) {
    std::string paint =
        "mark; xdotool key --window $w m; wait_handled 2 0; mark; xdotool key --window $w 5; "
        "wait_handled 2 0;";
    if (xray) paint += " mark; xdotool key --window $w x; wait_handled 2 0;";
    const long y = std::lround(mid.y());
    paint += " mark; xdotool mousemove --window $w " + std::to_string(std::lround(left) - 8) + " " + std::to_string(y) +
             " sleep 0.1 mousedown 1";
    for (double x = left - 8; x <= right + 8; x += 10)
      paint += " mousemove --window $w " + std::to_string(std::lround(x)) + " " + std::to_string(y) + " sleep 0.03";
    paint +=
        " mouseup 1; wait_handled 0 2; mark; xdotool key --window $w c; wait_handled 2 0; mark; "
        "xdotool key --window $w m; wait_handled 2 0;";
    const fs::path log = dir / (xray ? "xray_cut.log" : "plain_cut.log");
    REQUIRE(run_under_xvfb(xdotool_session("--source " + cactus.string() + " --target " + other.string(), paint) +
                           " 2> " + log.string()) == 0);
    return text_of(log);
  };
  const std::string plain = cut_log(false), xray = cut_log(true);
  CAPTURE(plain);
  CAPTURE(xray);
  auto kept = [](const std::string& log) {
    const std::string tag = "cut: the source keeps ";
    const size_t at = log.find(tag);
    return at == std::string::npos ? -1 : std::stoi(log.substr(at + tag.size()));
  };
  const int half = kept(plain), all_round = kept(xray);
  MESSAGE("the cut source keeps " << half << " vertices painted plainly, " << all_round << " with x-ray, of "
                                  << source.num_vertices());
  CHECK(half > 0);
  CHECK(half < source.num_vertices() / 4);  // a patch of the front
  CHECK(all_round > 2 * half);
  CHECK(all_round > source.num_vertices() / 2);
  CHECK(xray.find("1 boundary loop(s)") != std::string::npos);
  CHECK(xray.find("not manifold") == std::string::npos);
}

TEST_CASE("apps: merge app — dependent mode keeps a picked handle fixed and exports what lapis merge needs") {
  const fs::path dir = scratch_dir(), prefix = dir / "dependent";
  const DefaultScene scene;
  const std::string actions = scene.pair_and_key() + scene.click_handle(scene.far_handle()) +
                              "mark; xdotool key --window $w d; wait_handled 2 0; "
                              "mark; xdotool key --window $w m; wait_handled 2 0;";
  REQUIRE(run_under_xvfb(xdotool_session("--export " + prefix.string(), actions)) == 0);
  const Exported e = read_exports(prefix);
  CHECK(e.command.find("--mode dependent --handles " + prefix.string() + "_handles.json") != std::string::npos);
  // Dependent merging keeps the placement and the handles exactly.
  check_one_handle_kept(e, prefix);
  check_watertight_seam(e);
  check_equals_cli(e, dir / "dependent_cli.obj");
}

TEST_CASE("apps: merge app — undo takes the clicked key back to the suggested one, redo restores the merge") {
  const fs::path dir = scratch_dir(), events = dir / "undo_redo.json", log = dir / "undo_redo.log",
                 prefix = dir / "redone";
  // The recorded session, then Ctrl+Z, M, Ctrl+Shift+Z, M.
  constexpr int kZ = 90, kCtrl = 2, kShift = 1;
  write_recorded_session_then_keys(events, {{kZ, kCtrl}, {kM, 0}, {kZ, kCtrl | kShift}, {kM, 0}});
  REQUIRE(run_under_xvfb(kApp + " --headless --replay " + events.string() + " --exit-after-replay --export " +
                         prefix.string() + " 2> " + log.string()) == 0);
  const std::string text = text_of(log);
  // The pair had the suggested key before the click, so the undone setup still merges.
  CHECK(text.find("pair 1: key suggested") != std::string::npos);
  CHECK(text.find("undo: key correspondence") != std::string::npos);
  CHECK(text.find("merge failed") == std::string::npos);
  CHECK(text.find("redo: key correspondence") != std::string::npos);
  const Exported e = read_exports(prefix);
  REQUIRE(e.pairs.size() == 1);
  CHECK(e.pairs[0].keys.size() == 1);
  check_watertight_seam(e);
  check_equals_cli(e, dir / "redone_cli.obj");
}

TEST_CASE("apps: merge app — transition regions (T) merge watertight and export the widths lapis merge needs") {
  const fs::path dir = scratch_dir(), events = dir / "transition.json", prefix = dir / "transition";
  // The recorded session, then T (transition regions on, suggested widths) and M.
  write_recorded_session_then_keys(events, {{kT, 0}, {kM, 0}});
  REQUIRE(run_under_xvfb(kApp + " --headless --replay " + events.string() + " --exit-after-replay --export " +
                         prefix.string()) == 0);
  const Exported e = read_exports(prefix);
  CHECK(e.command.find("--mode transition --source-width ") != std::string::npos);
  CHECK(e.command.find("--keep source") != std::string::npos);
  check_watertight_seam(e);
  check_equals_cli(e, dir / "transition_cli.obj");
}

TEST_CASE("apps: merge app — a non-manifold source is refused with the module's message, not a crash") {
  const fs::path dir = scratch_dir(), bad = dir / "fin.obj", events = dir / "merge_now.json", log = dir / "fin.log";
  {
    std::ofstream out(bad);  // three triangles on the edge (0, 1): a fin, open but not manifold
    out << "v 0 0 0\nv 1 0 0\nv 0.5 1 0\nv 0.5 -1 0\nv 0.5 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n";
  }
  write_merge_key_events(events);
  REQUIRE(run_under_xvfb(kApp + " --headless --source " + bad.string() + " --target " +
                         (kSource / "assets/merge/neck.obj").string() + " --replay " + events.string() +
                         " --exit-after-replay 2> " + log.string()) == 0);
  CHECK(text_of(log).find("merge failed: mesh_merge::check_merge_input(): the source is not manifold") !=
        std::string::npos);
}

TEST_CASE("apps: merge app — the optimal boundary from a regions file: search, merge, export, equal to lapis merge") {
  const fs::path dir = scratch_dir(), prefix = dir / "optimal", shot = dir / "optimal.png";
  const std::string inputs = " --source " + (kSource / "assets/merge/bump.obj").string() + " --target " +
                             (kSource / "assets/merge/plate.obj").string() + " --regions " +
                             (kSource / "assets/merge/bump_regions.json").string();
  REQUIRE(run_under_xvfb(xdotool_session(inputs + " --export " + prefix.string(),
                                         "mark; xdotool key --window $w m; wait_handled 2 0;"
                                         " mark; xdotool key --window $w ctrl+e; wait_handled 4 0;")) == 0);
  const std::string command = text_of(prefix.string() + "_command.txt");
  CHECK(command.find("--mode optimal") != std::string::npos);
  CHECK(command.find("--regions " + prefix.string() + "_regions.json") != std::string::npos);
  Exported e;
  e.merged = geometry::read_mesh(prefix.string() + ".obj");
  e.command = command.substr(0, command.find('\n'));
  const geometry::TriMesh plate = asset("plate.obj");
  CHECK(e.merged.num_vertices() > plate.num_vertices());
  // Watertight: the plate's border is the only boundary left.
  CHECK(geometry::Connectivity(e.merged).boundary_loops().size() == 1);
  check_equals_cli(e, dir / "optimal_cli.obj");
  // Headless, the merged bump with both boundaries on the ghost of the source.
  REQUIRE(run_under_xvfb(kApp + kSize + inputs + " --headless --replay " +
                         (kSource / "tests/apps/data/merge_key_m.json").string() + " --screenshot " + shot.string()) ==
          0);
  CHECK(foreground_fraction(viewer::read_png(shot)) > 0.03);
}

TEST_CASE(
    "apps: merge app — in the optimal-boundary mode the brush grows the feature and the placement view moves the "
    "band") {
  const fs::path dir = scratch_dir(), prefix = dir / "placed";
  const fs::path bump = kSource / "assets/merge/bump.obj", plate = kSource / "assets/merge/plate.obj",
                 regions = kSource / "assets/merge/bump_regions.json";
  const geometry::TriMesh source = geometry::read_mesh(bump), target = geometry::read_mesh(plate);
  const geometry::CameraMatrices cam = first_view(source, target);
  const Eigen::Vector3d top = geometry::project(cam, Eigen::Vector3d(0, 0, 0.25));
  REQUIRE(top.x() < kWidth - merge_app::kPanelWidth);
  // Tool 5 paints the chosen region, the feature by default: a stroke across the bump.
  std::string actions = "mark; xdotool key --window $w 5; wait_handled 2 0; mark; xdotool mousemove --window $w " +
                        pixel(top) + " sleep 0.1 mousedown 1";
  for (int k = 1; k <= 6; ++k)
    actions += " mousemove --window $w " + std::to_string(std::lround(top.x()) + 6 * k) + " " +
               std::to_string(std::lround(top.y())) + " sleep 0.05";
  actions += " mouseup 1; wait_handled 0 2;";
  // The placement view's canvas, bottom left (MergeApp::draw_placement_window): drag the band right.
  const Eigen::Vector2i canvas(170, kHeight - 330 + 27 + 130);
  actions += " mark; xdotool mousemove --window $w " + std::to_string(canvas.x()) + " " + std::to_string(canvas.y()) +
             " sleep 0.1 mousedown 1";
  for (int k = 1; k <= 5; ++k)
    actions += " mousemove --window $w " + std::to_string(canvas.x() + 4 * k) + " " + std::to_string(canvas.y()) +
               " sleep 0.05";
  actions +=
      " mouseup 1; wait_handled 0 2; mark; xdotool key --window $w m; wait_handled 2 0;"
      " mark; xdotool key --window $w ctrl+e; wait_handled 4 0;";
  REQUIRE(run_under_xvfb(xdotool_session("--source " + bump.string() + " --target " + plate.string() + " --regions " +
                                             regions.string() + " --export " + prefix.string(),
                                         actions)) == 0);
  const nlohmann::json given = nlohmann::json::parse(text_of(regions)),
                       exported = nlohmann::json::parse(text_of(prefix.string() + "_regions.json"));
  MESSAGE("feature faces: " << given["feature"]["faces"].size() << " given, " << exported["feature"]["faces"].size()
                            << " exported");
  CHECK(exported["feature"]["faces"].size() > given["feature"]["faces"].size() + 20);  // not only the round trip's one
  const std::string command = text_of(prefix.string() + "_command.txt");
  Exported e;
  e.merged = geometry::read_mesh(prefix.string() + ".obj");
  e.command = command.substr(0, command.find('\n'));
  check_equals_cli(e, dir / "placed_cli.obj");
  // The dragged placement is not the suggested one: the plain merge of the same regions differs.
  const std::string at = command.substr(command.find("--placement ") + 12);
  const std::string placement = at.substr(0, at.find(' '));
  REQUIRE(run(kCli + " merge --mode optimal --source " + bump.string() + " --target " + plate.string() + " --regions " +
              prefix.string() + "_regions.json --out " + (dir / "suggested.obj").string() + " > " +
              (dir / "suggested.json").string()) == 0);
  const nlohmann::json suggested = nlohmann::json::parse(text_of(dir / "suggested.json"));
  const double u = std::stod(placement.substr(placement.find(',', placement.find(',') + 1) + 1));
  CHECK(u > suggested["placement"]["u"].get<double>() + 0.01);
}

// A key on the far side of the loop merges the dome turned over; the result is flagged. K then
// suggests the key as the dome is placed, and the merge with it is not flagged.
TEST_CASE("apps: merge app — a key half the loop away is flagged FLIPPED; K suggests the key that merges upright") {
  const fs::path dir = scratch_dir(), prefix = dir / "suggested", log = dir / "suggested.log";
  const DefaultScene scene;
  // The key K suggests, and a flipped one: a source loop vertex whose pixel is clear of every
  // other loop vertex (the click picks the nearest; loops are drawn on top), onto the target
  // vertex half the loop away from where the suggestion takes it (by loop index, both loops
  // evenly sampled).
  const mesh_merge::KeySuggestion s =
      mesh_merge::suggest_key(scene.source, Eigen::Matrix4d::Identity(), scene.sloop, scene.target, scene.tloop);
  auto index_in = [](const std::vector<int>& loop, int v) {
    return static_cast<long>(std::find(loop.begin(), loop.end(), v) - loop.begin());
  };
  auto pixel_of = [&](const geometry::TriMesh& m, int v) {
    return geometry::project(scene.camera, m.V.row(v).transpose()).head<2>().eval();
  };
  auto clearance = [&](const geometry::TriMesh& m, int vertex) {
    double d = 1e9;
    for (int v : scene.sloop)
      if (&m != &scene.source || v != vertex) d = std::min(d, (pixel_of(scene.source, v) - pixel_of(m, vertex)).norm());
    for (int v : scene.tloop)
      if (&m != &scene.target || v != vertex) d = std::min(d, (pixel_of(scene.target, v) - pixel_of(m, vertex)).norm());
    return d;
  };
  const long ns = static_cast<long>(scene.sloop.size()), nt = static_cast<long>(scene.tloop.size());
  int key_s = -1, key_t = -1;
  for (int v : scene.sloop) {
    const long ds = (index_in(scene.sloop, v) - index_in(scene.sloop, s.key.source) + ns) % ns;
    const int t =
        scene.tloop[static_cast<size_t>((index_in(scene.tloop, s.key.target) - ds * nt / ns + nt / 2 + 2 * nt) % nt)];
    if (clearance(scene.source, v) > 3 && clearance(scene.target, t) > 3) {
      key_s = v, key_t = t;
      break;
    }
  }
  REQUIRE(key_s >= 0);
  auto rounded = [&](const geometry::TriMesh& m, int v) {
    const Eigen::Vector2d p = pixel_of(m, v);
    return Eigen::Vector2i(static_cast<int>(std::lround(p.x())), static_cast<int>(std::lround(p.y())));
  };
  const Eigen::Vector2i key_source = rounded(scene.source, key_s), key_target = rounded(scene.target, key_t);
  // Pair the loops, then click the flipped key.
  const std::string clicks = click(scene.front_pixel(scene.source, scene.sloop)) +
                             click(scene.front_pixel(scene.target, scene.tloop)) + click(key_source) +
                             click(key_target);
  const std::string keys =
      "mark; xdotool key --window $w m; wait_handled 2 0\n"
      "mark; xdotool key --window $w k; wait_handled 2 0\n"
      "mark; xdotool key --window $w m; wait_handled 2 0\n"
      "mark; xdotool key --window $w ctrl+e; wait_handled 4 0\n";
  REQUIRE(run_under_xvfb(xdotool_session("--export " + prefix.string(),
                                         clicks + "xdotool mousemove --window $w 300 600\n" + keys) +
                         " 2> " + log.string()) == 0);
  const std::string text = text_of(log);
  CAPTURE(text);
  // The clicked key turned the dome over: flagged.
  const size_t flipped = text.find("lapis-merge: FLIPPED: the merge turned the source ");
  CHECK(flipped != std::string::npos);
  // K's suggestion (the second: the first came with the pair) ends it; no merge after is flagged.
  const size_t suggested = text.find("pair 1: key suggested", text.find("pair 1: key suggested") + 1);
  REQUIRE(suggested != std::string::npos);
  CHECK(flipped < suggested);
  CHECK(text.find("FLIPPED", suggested) == std::string::npos);
  // The export holds K's key: suggest_key's for the dome as placed.
  const Exported e = read_exports(prefix);
  REQUIRE(e.pairs.size() == 1);
  REQUIRE(e.pairs[0].keys.size() == 1);
  CHECK(e.pairs[0].keys[0].source == s.key.source);
  CHECK(e.pairs[0].keys[0].target == s.key.target);
  check_watertight_seam(e);
}

// §3.3.3 on §3.3.2's boundary condition from the keyboard: T, then D turns the bands'
// boundary condition dependent, where the handles clicked with tool 3 stay where they were placed.
TEST_CASE("apps: merge app — transition regions on the dependent boundary (T, D) keep a handle, equal to lapis merge") {
  const fs::path dir = scratch_dir(), prefix = dir / "transition_dependent";
  const DefaultScene scene;
  // The top: a handle in the source's transition band is refused.
  const std::string actions = scene.pair_and_key() + scene.click_handle(scene.apex()) +
                              "mark; xdotool key --window $w t; wait_handled 2 0; "
                              "mark; xdotool key --window $w d; wait_handled 2 0; "
                              "mark; xdotool key --window $w m; wait_handled 2 0;";
  REQUIRE(run_under_xvfb(xdotool_session("--export " + prefix.string(), actions)) == 0);
  const Exported e = read_exports(prefix);
  CHECK(e.command.find("--mode transition --source-width ") != std::string::npos);
  CHECK(e.command.find("--transition-boundary dependent --handles " + prefix.string() + "_handles.json") !=
        std::string::npos);
  // §3.3.1's condition would move the handle with the rest of the source.
  check_one_handle_kept(e, prefix);
  check_watertight_seam(e);
  check_equals_cli(e, dir / "transition_dependent_cli.obj");
}

// §3.5 from the window: tool 5 paints the dome's top, A makes it a fixed feature, and the export
// carries it to lapis merge --features.
TEST_CASE("apps: merge app — a region painted on the source and added with A merges as a fixed feature") {
  const fs::path dir = scratch_dir(), prefix = dir / "feature";
  const DefaultScene scene;
  const int apex = scene.apex();
  const Eigen::Vector3d top = geometry::project(scene.camera, scene.source.V.row(apex).transpose());
  std::string actions =
      scene.pair_and_key() + "mark; xdotool key --window $w 5; wait_handled 2 0; mark; xdotool mousemove --window $w " +
      std::to_string(std::lround(top.x()) - 12) + " " + std::to_string(std::lround(top.y())) + " sleep 0.1 mousedown 1";
  for (int k = 1; k <= 6; ++k)
    actions += " mousemove --window $w " + std::to_string(std::lround(top.x()) - 12 + 4 * k) + " " +
               std::to_string(std::lround(top.y())) + " sleep 0.05";
  actions +=
      " mouseup 1; wait_handled 0 2; mark; xdotool key --window $w a; wait_handled 2 0;"
      " mark; xdotool key --window $w m; wait_handled 2 0; mark; xdotool key --window $w ctrl+e; wait_handled 4 0;";
  REQUIRE(run_under_xvfb(xdotool_session("--export " + prefix.string(), actions)) == 0);
  const Exported e = read_exports(prefix);
  CHECK(e.command.find("--features " + prefix.string() + "_features.json") != std::string::npos);
  const std::vector<std::vector<int>> features = mesh_merge::read_features_file(prefix.string() + "_features.json");
  REQUIRE(features.size() == 1);
  CHECK(features[0].size() >= 4);
  CHECK(std::find(features[0].begin(), features[0].end(), apex) != features[0].end());
  check_watertight_seam(e);
  check_equals_cli(e, dir / "feature_cli.obj");
}

// The optimal mode's other regions and gestures: R picks the target region, then the rough one,
// and a stroke grows each; in the placement view the wheel scales the band and a right-drag
// turns it. The export reproduces all of it.
TEST_CASE("apps: merge app — R paints the target and rough regions; the wheel scales and a right-drag turns the band") {
  const fs::path dir = scratch_dir(), prefix = dir / "regions", regions = dir / "given_regions.json";
  const fs::path bump = kSource / "assets/merge/bump.obj", plate = kSource / "assets/merge/plate.obj";
  const geometry::TriMesh source = geometry::read_mesh(bump), target = geometry::read_mesh(plate);
  // The bundled regions with a target disk of radius 1.2 on the plate (the bundled one is all of it).
  nlohmann::json given = nlohmann::json::parse(text_of(kSource / "assets/merge/bump_regions.json"));
  std::vector<int> disk;
  for (int f = 0; f < target.num_faces(); ++f) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int j = 0; j < 3; ++j) c += target.V.row(target.F(f, j)).transpose() / 3;
    if (c.head<2>().norm() < 1.2) disk.push_back(f);
  }
  given["target"] = {{"faces", disk}};
  std::ofstream(regions) << given.dump();
  const geometry::CameraMatrices cam = first_view(source, target);
  auto stroke = [&](const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
    const Eigen::Vector3d a = geometry::project(cam, from), b = geometry::project(cam, to);
    std::string s = "mark; xdotool mousemove --window $w " + pixel(a) + " sleep 0.1 mousedown 1";
    for (int k = 1; k <= 6; ++k) s += " mousemove --window $w " + pixel(a + (b - a) * k / 6.0) + " sleep 0.05";
    return s + " mouseup 1; wait_handled 0 2;";
  };
  // R: feature -> target region, a stroke on the plate outward from the disk; R: -> rough
  // region, a stroke on the bump outward from it.
  std::string actions = "mark; xdotool key --window $w r; wait_handled 2 0; " +
                        stroke(Eigen::Vector3d(0, -1.1, 0), Eigen::Vector3d(0, -1.45, 0)) +
                        " mark; xdotool key --window $w r; wait_handled 2 0; " +
                        stroke(Eigen::Vector3d(0, -0.8, 0), Eigen::Vector3d(0, -0.98, 0));
  // The placement view's canvas (MergeApp::draw_placement_window): scroll up once, then turn.
  const Eigen::Vector2i canvas(170, kHeight - 330 + 27 + 130);
  const std::string at = std::to_string(canvas.x()) + " " + std::to_string(canvas.y());
  actions += " mark; xdotool mousemove --window $w " + at + " sleep 0.1 click 4 sleep 0.1 mousedown 3";
  for (int k = 1; k <= 10; ++k)
    actions += " mousemove --window $w " + std::to_string(canvas.x() + 6 * k) + " " + std::to_string(canvas.y()) +
               " sleep 0.05";
  actions +=
      " mouseup 3; wait_handled 0 2; mark; xdotool key --window $w m; wait_handled 2 0;"
      " mark; xdotool key --window $w ctrl+e; wait_handled 4 0;";
  REQUIRE(run_under_xvfb(xdotool_session("--source " + bump.string() + " --target " + plate.string() + " --regions " +
                                             regions.string() + " --export " + prefix.string(),
                                         actions)) == 0);
  const nlohmann::json exported = nlohmann::json::parse(text_of(prefix.string() + "_regions.json"));
  // Regions are exported as faces of the painted vertices: compare face counts.
  const size_t target_given = disk.size(), rough_given = given["rough"]["faces"].size();
  MESSAGE("target faces " << target_given << " -> " << exported["target"]["faces"].size() << ", rough faces "
                          << rough_given << " -> " << exported["rough"]["faces"].size());
  CHECK(exported["target"]["faces"].size() > target_given + 10);
  CHECK(exported["rough"]["faces"].size() > rough_given + 5);
  const std::string command = text_of(prefix.string() + "_command.txt");
  Exported e;
  e.merged = geometry::read_mesh(prefix.string() + ".obj");
  e.command = command.substr(0, command.find('\n'));
  check_equals_cli(e, dir / "regions_cli.obj");
  CHECK(geometry::Connectivity(e.merged).boundary_loops().size() == 1);
  // The placement against the suggested one for the same regions: scaled by the wheel's 1.1,
  // turned by the drag (0.01 rad per pixel: 34° for its 60 pixels, less the moves a busy frame
  // reads before the canvas takes the drag).
  REQUIRE(run(kCli + " merge --mode optimal --source " + bump.string() + " --target " + plate.string() + " --regions " +
              prefix.string() + "_regions.json --out " + (dir / "suggested.obj").string() + " > " +
              (dir / "suggested.json").string()) == 0);
  const nlohmann::json suggested = nlohmann::json::parse(text_of(dir / "suggested.json"))["placement"];
  std::vector<double> p;
  std::stringstream words(command.substr(command.find("--placement ") + 12));
  for (std::string part; p.size() < 4 && std::getline(words, part, ',');) p.push_back(std::stod(part));
  REQUIRE(p.size() == 4);
  MESSAGE("placement scale " << p[0] << ", " << p[1] << " deg; suggested " << suggested["scale"] << ", "
                             << suggested["degrees"]);
  CHECK(p[0] == doctest::Approx(1.1 * suggested["scale"].get<double>()).epsilon(1e-6));
  CHECK(p[1] - suggested["degrees"].get<double>() > 2);
}
