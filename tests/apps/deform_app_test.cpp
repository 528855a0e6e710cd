// The deform app, for real: under Xvfb, a gizmo drag with xdotool, an export through Ctrl+E
// checked against `lapis deform` on the files the app wrote, and headless screenshots.
#include <doctest/doctest.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>

#include "app_runner.h"
#include "lapis/geometry/bvh.h"
#include "lapis/geometry/connectivity.h"
#include "lapis/geometry/geodesic_disc.h"
#include "lapis/geometry/io.h"
#include "lapis/geometry/laplacian.h"
#include "lapis/geometry/mirror_vertices.h"
#include "lapis/geometry/procedural.h"
#include "lapis/geometry/region_border.h"
#include "lapis/mesh_deform/metrics.h"
#include "lapis/mesh_deform/selection_io.h"
#include "lapis/viewer/gizmo.h"
#include "lapis/viewer/input_events.h"
#include "lapis/viewer/orbit_camera.h"
#include "lapis/viewer/picking.h"
#include "lapis/viewer/surface_select.h"
#include "transfer_pairing.h"

using namespace lapis;
using namespace lapis::apps_test;

namespace {

const std::string kApp = LAPIS_DEFORM_APP_EXE, kCli = LAPIS_CLI_EXE;
const fs::path kSource = LAPIS_SOURCE_DIR;
const fs::path kData = kSource / "tests/apps/data";
const fs::path kMesh = kSource / "assets/external/camel.off";
const fs::path kRoi = kData / "deform_camel.roi.txt", kHandles = kData / "deform_camel.handles.json";
constexpr int kWidth = 900, kHeight = 700;
const std::string kSize = " --size " + std::to_string(kWidth) + "x" + std::to_string(kHeight);

// The app's first view: the orbit camera framed on the bounds of what it shows.
geometry::CameraMatrices initial_camera(const geometry::Vertices& shown, int width = kWidth, int height = kHeight) {
  viewer::OrbitCamera cam;
  cam.frame(shown.colwise().minCoeff().transpose(), shown.colwise().maxCoeff().transpose());
  return cam.matrices(width, height);
}
geometry::CameraMatrices initial_camera(const geometry::TriMesh& mesh) { return initial_camera(mesh.V); }

Eigen::Vector2d pixel(const geometry::CameraMatrices& cam, const Eigen::Vector3d& p) {
  return geometry::project(cam, p).head<2>();
}

std::string xy(const Eigen::Vector2d& p) {
  return std::to_string(static_cast<int>(std::lround(p.x()))) + " " +
         std::to_string(static_cast<int>(std::lround(p.y())));
}

Eigen::Vector2d rounded(const Eigen::Vector2d& p) { return {std::lround(p.x()), std::lround(p.y())}; }

// A drag along one gizmo arrow, planned from the app's first view.
struct PlannedDrag {
  int axis = -1;
  Eigen::Vector2d from, to;  // pixels
  double expected = 0;       // world translation along the axis the gizmo maps it to
};

PlannedDrag plan_drag(const geometry::TriMesh& mesh, const std::vector<int>& handle,
                      const geometry::CameraMatrices& cam, int width = kWidth, int height = kHeight) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int v : handle) c += mesh.V.row(v).transpose();
  c /= static_cast<double>(handle.size());
  viewer::Gizmo gizmo;
  gizmo.set_center(c);
  const double L = gizmo.world_size(cam);
  PlannedDrag best;
  double longest = 0;
  auto usable = [&](const Eigen::Vector2d& p) {  // in the 3D view, clear of the panels
    return p.x() > 20 && p.x() < width - 350 && p.y() > 150 && p.y() < height - 20;
  };
  for (int a = 0; a < 3; ++a) {
    // Grab the arrow at 80% of its length and pull it 120 px along the arrow's own screen
    // direction, outwards or back (whichever stays in the view); prefer the axis that shows
    // longest on screen.
    const Eigen::Vector3d axis = Eigen::Vector3d::Unit(a);
    const Eigen::Vector2d p0 = pixel(cam, c), p1 = pixel(cam, c + L * axis);
    if ((p1 - p0).norm() <= longest) continue;
    const Eigen::Vector2d from = rounded(pixel(cam, c + 0.8 * L * axis));
    for (double sign : {1.0, -1.0}) {
      const Eigen::Vector2d to = rounded(from + sign * 120 * (p1 - p0).normalized());
      if (!usable(from) || !usable(to)) continue;
      longest = (p1 - p0).norm();
      best.axis = a, best.from = from, best.to = to;
      const auto t0 = viewer::closest_axis_parameter(geometry::unproject_ray(cam, from.x(), from.y()), c, axis);
      const auto t1 = viewer::closest_axis_parameter(geometry::unproject_ray(cam, to.x(), to.y()), c, axis);
      best.expected = *t1 - *t0;
      break;
    }
  }
  return best;
}

double max_difference(const geometry::Vertices& a, const geometry::Vertices& b) {
  return (a - b).cwiseAbs().maxCoeff();
}

// Runs the app in a visible window under Xvfb: waits until it has drawn and finished its
// setup (--ready-file), runs `actions` (xdotool, with $w the window), waits for `wait_for` to
// exist (up to 240 s), quits.
int run_window(const std::string& app_args, const std::string& actions, const fs::path& wait_for,
               const std::string& size = kSize) {
  const fs::path dir = scratch_dir();
  const std::string body = kApp + size + " " + app_args + " --ready-file " + (dir / "deform.ready").string() +
                           " &\napp=$!\n"
                           "window lapis-deform || { kill $app; exit 3; }\n"
                           "wait_ready '[ $busy -eq 0 ]' || { kill $app; exit 4; }\n" +
                           actions + "\nfor i in $(seq 1 2400); do [ -e " + wait_for.string() +
                           " ] && break; sleep 0.1; done\n"
                           "quit_discarding\n";
  return run_under_xvfb(ready_script(dir / "deform.sh", dir / "deform.ready", body));
}

// Builds an event log frame by frame (GLFW codes: keys, buttons, Ctrl).
struct EventScript {
  static constexpr int kKeyB = 66, kKeyL = 76, kKey2 = 50, kKey3 = 51, kKeyEqual = 61, kKeyZ = 90, kKeyS = 83;
  static constexpr int kCtrl = 2, kShift = 1;
  viewer::EventLog log;
  long frame = 10;  // after the app has opened the mesh and the selection

  void add(viewer::InputEvent e) {
    e.frame = frame;
    log.events.push_back(e);
  }
  void key(int code, int mods = 0) {
    for (int action : {1, 0}) {
      viewer::InputEvent e{viewer::EventType::Key};
      e.key = code, e.action = action, e.mods = mods;
      add(e);
      ++frame;
    }
  }
  void move(const Eigen::Vector2d& p) {
    viewer::InputEvent e{viewer::EventType::MouseMove};
    e.x = p.x(), e.y = p.y();
    add(e);
    ++frame;
  }
  void button(const Eigen::Vector2d& p, int action) {
    viewer::InputEvent e{viewer::EventType::MouseButton};
    e.x = p.x(), e.y = p.y(), e.button = 0, e.action = action;
    add(e);
    ++frame;
  }
  // Left-drag through the points.
  void drag(const std::vector<Eigen::Vector2d>& path) {
    move(path.front());
    button(path.front(), 1);
    for (const auto& p : path) move(p);
    button(path.back(), 0);
  }
};

std::string text_of(const fs::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<int> complement(const std::vector<int>& set, int n) {
  std::vector<char> in(static_cast<size_t>(n), 0);
  for (int v : set) in[static_cast<size_t>(v)] = 1;
  std::vector<int> out;
  for (int v = 0; v < n; ++v)
    if (!in[static_cast<size_t>(v)]) out.push_back(v);
  return out;
}

}  // namespace

TEST_CASE("apps: deform app — lasso a handle, brush the fixed feet, grow, undo, save: the files say so") {
  const fs::path dir = scratch_dir();
  const geometry::TriMesh mesh = geometry::read_mesh(kMesh);
  const geometry::CameraMatrices cam = initial_camera(mesh);
  // The lasso: a rectangle around the head (the vertices the saved test selection's handle holds).
  const std::vector<int> head = mesh_deform::read_handles(kHandles).selection.region_handles.at(0);
  Eigen::Vector2d lo(1e9, 1e9), hi(-1e9, -1e9);
  for (int v : head) {
    const Eigen::Vector2d p = pixel(cam, mesh.V.row(v).transpose());
    lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  }
  lo = rounded(lo.array() - 4), hi = rounded(hi.array() + 4);
  const std::vector<Eigen::Vector2d> rect{lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}};
  // The brush: a stroke across the feet, 24 px (the default radius) deep.
  Eigen::Vector2d left(1e9, 0), right(-1e9, 0);
  const double foot_y = mesh.V.col(1).minCoeff() + 0.03;
  for (int v = 0; v < mesh.num_vertices(); ++v)
    if (mesh.V(v, 1) < foot_y) {
      const Eigen::Vector2d p = pixel(cam, mesh.V.row(v).transpose());
      if (p.x() < left.x()) left = p;
      if (p.x() > right.x()) right = p;
    }
  left = rounded(left), right = rounded(right);
  REQUIRE(right.x() - left.x() > 40);

  EventScript paint;
  paint.key(EventScript::kKeyL);
  paint.key(EventScript::kKey3);
  paint.drag({rect[0], rect[1], rect[2], rect[3], rect[0] + Eigen::Vector2d(0, 1)});
  paint.key(EventScript::kKeyB);
  paint.key(EventScript::kKey2);
  std::vector<Eigen::Vector2d> stroke;
  for (int k = 0; k <= 10; ++k) stroke.push_back(rounded(left + (right - left) * (k / 10.0)));
  paint.drag(stroke);
  paint.key(EventScript::kKeyS, EventScript::kCtrl);
  paint.frame += 5;
  paint.log.width = kWidth, paint.log.height = kHeight;
  paint.log.save(dir / "paint.json");
  const fs::path roi = dir / "sel.roi.txt", handles = dir / "sel.handles.json";
  const std::string files = " --mesh " + kMesh.string() + " --roi " + roi.string() + " --handles " + handles.string();
  REQUIRE(run_under_xvfb(kApp + " --headless" + files + " --replay " + (dir / "paint.json").string() +
                         " --exit-after-replay") == 0);

  // The handle: what the lasso enclosed and the camera saw.
  REQUIRE(fs::exists(handles));
  const mesh_deform::Drag saved = mesh_deform::read_handles(handles);
  REQUIRE(saved.selection.region_handles.size() == 1);
  const std::vector<int>& handle = saved.selection.region_handles[0];
  CHECK(handle.size() > 100);
  for (int v : handle) {
    const Eigen::Vector2d p = pixel(cam, mesh.V.row(v).transpose());
    CHECK(viewer::point_in_polygon(rect, p));
  }
  // The fixed region (outside the ROI, as no ROI was painted): within the brush of the stroke.
  const std::vector<int> fixed = complement(mesh_deform::read_roi(roi), mesh.num_vertices());
  CHECK(fixed.size() > 20);
  for (int v : fixed) {
    const Eigen::Vector2d p = pixel(cam, mesh.V.row(v).transpose());
    CHECK(viewer::distance_to_segment(p, left, right) < 24 + 4);  // + perspective across the feet
  }

  // Second run: open the saved files, grow the fixed region twice, undo once, redo nothing,
  // save: one ring more than before.
  fs::copy_file(roi, dir / "first.roi.txt");
  EventScript edit;
  edit.key(EventScript::kKey2);
  edit.key(EventScript::kKeyEqual);
  edit.key(EventScript::kKeyEqual);
  edit.key(EventScript::kKeyZ, EventScript::kCtrl);
  edit.key(EventScript::kKeyS, EventScript::kCtrl);
  edit.frame += 5;
  edit.log.width = kWidth, edit.log.height = kHeight;
  edit.log.save(dir / "edit.json");
  REQUIRE(run_under_xvfb(kApp + " --headless" + files + " --replay " + (dir / "edit.json").string() +
                         " --exit-after-replay") == 0);
  const std::vector<int> grown = complement(mesh_deform::read_roi(roi), mesh.num_vertices());
  const geometry::Connectivity conn(mesh);
  std::vector<int> expected = viewer::grow_rings(conn, fixed, 1);
  // Growth never takes handle vertices.
  std::vector<char> is_handle(static_cast<size_t>(mesh.num_vertices()), 0);
  for (int v : handle) is_handle[static_cast<size_t>(v)] = 1;
  std::erase_if(expected, [&](int v) { return is_handle[static_cast<size_t>(v)] != 0; });
  CHECK(grown == expected);
  CHECK(grown.size() > fixed.size());
}

TEST_CASE("apps: deform app — dragging the gizmo with xdotool moves the handle, and the export equals lapis deform") {
  const fs::path dir = scratch_dir();
  const geometry::TriMesh mesh = geometry::read_mesh(kMesh);
  const mesh_deform::Drag saved = mesh_deform::read_handles(kHandles);
  const std::vector<int> roi = mesh_deform::read_roi(kRoi);
  REQUIRE(saved.selection.region_handles.size() == 1);
  const std::vector<int>& handle = saved.selection.region_handles[0];
  const geometry::CameraMatrices cam = initial_camera(mesh);
  const PlannedDrag drag = plan_drag(mesh, handle, cam);
  REQUIRE(drag.axis >= 0);
  CAPTURE(drag.axis);
  CAPTURE(drag.from.transpose());
  CAPTURE(drag.to.transpose());

  // Press on the arrow, pull it in small steps (a person's drag), release, export with Ctrl+E.
  std::string actions = "mark; xdotool mousemove --window $w " + xy(drag.from) + " sleep 0.1 mousedown 1";
  for (int k = 1; k <= 20; ++k)
    actions += " mousemove --window $w " + xy(drag.from + (drag.to - drag.from) * (k / 20.0)) + " sleep 0.03";
  actions += " mouseup 1; wait_handled 0 2 || { kill $app; exit 5; }\nxdotool key --window $w ctrl+e";
  const fs::path out = dir / "dragged.obj";
  REQUIRE(run_window("--mesh " + kMesh.string() + " --roi " + kRoi.string() + " --handles " + kHandles.string() +
                         " --method implicit --export " + out.string(),
                     actions, dir / "dragged.deform.json") == 0);
  REQUIRE(fs::exists(out));
  const geometry::TriMesh result = geometry::read_mesh(out);
  REQUIRE(result.V.rows() == mesh.V.rows());

  // The handle followed the drag: along the dragged axis, by what the cursor covered on it.
  const Eigen::Vector3d axis = Eigen::Vector3d::Unit(drag.axis);
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int v : handle) mean += (result.V.row(v) - mesh.V.row(v)).transpose();
  mean /= static_cast<double>(handle.size());
  CAPTURE(mean.transpose());
  CAPTURE(drag.expected);
  CHECK(mean.dot(axis) * drag.expected > 0);                        // direction
  CHECK(std::abs(mean.dot(axis)) > 0.5 * std::abs(drag.expected));  // order of magnitude
  CHECK(std::abs(mean.dot(axis)) < 2.0 * std::abs(drag.expected));
  CHECK((mean - mean.dot(axis) * axis).norm() < 0.1 * std::abs(drag.expected));  // along the axis only
  // The fixed region (outside the ROI) did not move at all.
  std::vector<char> in_roi(static_cast<size_t>(mesh.num_vertices()), 0);
  for (int v : roi) in_roi[static_cast<size_t>(v)] = 1;
  int fixed = 0;
  for (int v = 0; v < mesh.num_vertices(); ++v)
    if (!in_roi[static_cast<size_t>(v)]) {
      ++fixed;
      CHECK((result.V.row(v) - mesh.V.row(v)).norm() == 0);
    }
  CHECK(fixed > 100);

  // The app recorded the transform of every frame it solved next to the export; the CLI run
  // on those files gives the same mesh.
  const mesh_deform::Drag recorded = mesh_deform::read_handles(dir / "dragged.handles.json");
  REQUIRE(!recorded.frames.empty());
  const Eigen::Matrix4d T = recorded.frames.back().regions.at(0);
  CHECK((T.topLeftCorner<3, 3>() - Eigen::Matrix3d::Identity()).norm() < 1e-12);
  CHECK(std::abs(T(drag.axis, 3) - mean.dot(axis)) < 1e-9);  // hard constraints: the handle moved exactly by T
  std::ifstream report(dir / "dragged.deform.json");
  const auto j = nlohmann::json::parse(report);
  CHECK(j["method"] == "implicit");
  const fs::path cli_out = dir / "cli.obj";
  REQUIRE(run(kCli + " deform --mesh " + kMesh.string() + " --roi " + (dir / "dragged.roi.txt").string() +
              " --handles " + (dir / "dragged.handles.json").string() + " --method implicit --weights " +
              j["weights"].get<std::string>() + " --out " + cli_out.string() + " > /dev/null") == 0);
  const geometry::TriMesh cli = geometry::read_mesh(cli_out);
  CHECK(max_difference(cli.V, result.V) < 1e-9);
}

TEST_CASE("apps: deform app — a replayed drag renders headless, neither blank nor the unedited scene") {
  const fs::path dir = scratch_dir();
  const std::string common = " --headless" + kSize + " --mesh " + kMesh.string() + " --roi " + kRoi.string() +
                             " --handles " + kHandles.string() + " --method implicit";
  const fs::path still = dir / "still.png", replayed = dir / "replayed.png", out = dir / "replayed.obj";
  REQUIRE(run_under_xvfb(kApp + common + " --screenshot " + still.string()) == 0);
  REQUIRE(run_under_xvfb(kApp + common + " --replay " + (kData / "deform_drag_events.json").string() +
                         " --exit-after-replay --screenshot " + replayed.string() + " --export " + out.string() +
                         " --export-on-exit") == 0);
  const viewer::Image a = viewer::read_png(still), b = viewer::read_png(replayed);
  CHECK(foreground_fraction(a) > 0.05);
  CHECK(foreground_fraction(b) > 0.05);
  REQUIRE(a.rgba.size() == b.rgba.size());
  size_t changed = 0;
  for (size_t k = 0; k < a.rgba.size(); k += 4)
    if (std::abs(a.rgba[k] - b.rgba[k]) + std::abs(a.rgba[k + 1] - b.rgba[k + 1]) +
            std::abs(a.rgba[k + 2] - b.rgba[k + 2]) >
        30)
      ++changed;
  CHECK(changed > a.rgba.size() / 4 / 100);  // over 1% of the pixels
  // The replay moved the handle: the exported mesh is not the rest mesh.
  const geometry::TriMesh rest = geometry::read_mesh(kMesh), moved = geometry::read_mesh(out);
  CHECK(max_difference(rest.V, moved.V) > 1e-3);
}

// Coloured by distortion on a fixed range, the same replayed drag reads hot where the range is
// tiny and cold where it is huge; a range that followed each frame's p95 would colour both alike.
TEST_CASE("apps: deform app — a fixed distortion range colours the same drag hot or cold by the range") {
  const fs::path dir = scratch_dir(), events = dir / "drag_without_c.json";
  {  // the recorded drag without its C (colour toggle): --distortion-range opens in distortion colours
    std::ifstream in(kData / "deform_drag_events.json");
    nlohmann::json j = nlohmann::json::parse(in);
    auto& list = j["events"];
    list.erase(
        std::remove_if(list.begin(), list.end(), [](const nlohmann::json& e) { return e.value("key", 0) == 67; }),
        list.end());
    std::ofstream(events) << j.dump();
  }
  const std::string common = " --headless" + kSize + " --mesh " + kMesh.string() + " --roi " + kRoi.string() +
                             " --handles " + kHandles.string() + " --method implicit --replay " + events.string() +
                             " --exit-after-replay";
  // Pixels of the colour map's warm end (orange to red) and of its cold end (blue).
  auto warm_and_cold = [&](const std::string& range) {
    const fs::path shot = dir / ("range_" + range + ".png");
    REQUIRE(run_under_xvfb(kApp + common + " --distortion-range " + range + " --screenshot " + shot.string()) == 0);
    const viewer::Image im = viewer::read_png(shot);
    long warm = 0, cold = 0;
    for (size_t k = 0; k < im.rgba.size(); k += 4) {
      warm += im.rgba[k] > im.rgba[k + 2] + 80;
      cold += im.rgba[k + 2] > im.rgba[k] + 80;
    }
    return std::pair{warm, cold};
  };
  const auto [tiny_warm, tiny_cold] = warm_and_cold("1e-5");
  const auto [huge_warm, huge_cold] = warm_and_cold("1000");
  MESSAGE("warm / cold pixels: " << tiny_warm << " / " << tiny_cold << " on [0, 1e-5], " << huge_warm << " / "
                                 << huge_cold << " on [0, 1000]");
  CHECK(tiny_warm > huge_warm + 10000);  // every distorted vertex at the top of the map
  CHECK(huge_cold > tiny_cold + 10000);  // every vertex at the bottom
}

TEST_CASE("apps: deform app — the salient method shows its features and deforms a replayed drag") {
  const fs::path dir = scratch_dir();
  const std::string common = " --headless" + kSize + " --mesh " + kMesh.string() + " --roi " + kRoi.string() +
                             " --handles " + kHandles.string() + " --method salient";
  const fs::path shot = dir / "salient.png", out = dir / "salient.obj";
  REQUIRE(run_under_xvfb(kApp + common + " --replay " + (kData / "deform_drag_events.json").string() +
                         " --exit-after-replay --screenshot " + shot.string() + " --export " + out.string() +
                         " --export-on-exit") == 0);
  CHECK(foreground_fraction(viewer::read_png(shot)) > 0.05);
  const geometry::TriMesh rest = geometry::read_mesh(kMesh), moved = geometry::read_mesh(out);
  CHECK(max_difference(rest.V, moved.V) > 1e-3);
  // The export's report names the method, as the CLI would run it.
  std::ifstream report(dir / "salient.deform.json");
  REQUIRE(report);
  const auto j = nlohmann::json::parse(report);
  CHECK(j.dump().find("salient") != std::string::npos);
}

TEST_CASE("apps: deform app — bad input is reported, not a crash") {
  const fs::path dir = scratch_dir();
  std::ofstream(dir / "bad.off") << "OFF\n3 1 0\n0 0 0\n1 0 0\n";
  CHECK(run(kApp + " --mesh " + (dir / "bad.off").string() + " --headless 2> " + (dir / "err.txt").string()) == 1);
  std::ifstream err(dir / "err.txt");
  const std::string text((std::istreambuf_iterator<char>(err)), std::istreambuf_iterator<char>());
  CHECK(text.find("lapis-deform: error:") == 0);
  CHECK(text.find("bad.off") != std::string::npos);
  // A handle outside the mesh: the app starts, says why, exports nothing, and the batch run
  // that asked for the export fails.
  std::ofstream(dir / "h.json")
      << R"({"regions": [{"vertices": [999999], "transforms": [[[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]]}]})";
  std::ofstream(dir / "roi.txt") << "1 2 3";
  REQUIRE(run_under_xvfb(kApp + " --headless --mesh " + kMesh.string() + " --roi " + (dir / "roi.txt").string() +
                         " --handles " + (dir / "h.json").string() + " --export " + (dir / "none.obj").string() +
                         " --export-on-exit --screenshot " + (dir / "err.png").string() + " 2> " +
                         (dir / "err2.txt").string()) == 1);
  std::ifstream err2(dir / "err2.txt");
  const std::string text2((std::istreambuf_iterator<char>(err2)), std::istreambuf_iterator<char>());
  CHECK(text2.find("out of range") != std::string::npos);
  CHECK(!fs::exists(dir / "none.obj"));
  // A handle outside the ROI: the message `lapis deform` gives for the same files.
  std::ofstream(dir / "h2.json")
      << R"({"regions": [{"vertices": [7], "transforms": [[[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]]}]})";
  REQUIRE(run_under_xvfb(kApp + " --headless --mesh " + kMesh.string() + " --roi " + (dir / "roi.txt").string() +
                         " --handles " + (dir / "h2.json").string() + " --screenshot " + (dir / "err3.png").string() +
                         " 2> " + (dir / "err3.txt").string()) == 0);
  std::ifstream err3(dir / "err3.txt");
  const std::string text3((std::istreambuf_iterator<char>(err3)), std::istreambuf_iterator<char>());
  CHECK(text3.find("mesh_deform::Deformer::precompute(): region handle 0 vertex 7 is outside the ROI") !=
        std::string::npos);
}

TEST_CASE("apps: deform app — a headless export that cannot be written fails the run, naming the cause") {
  const fs::path dir = scratch_dir();
  std::ofstream(dir / "a_file") << "not a directory";
  const fs::path log = dir / "export_failed.log";
  const int status =
      run_under_xvfb(kApp + " --headless" + kSize + " --mesh " + kMesh.string() + " --roi " + kRoi.string() +
                     " --handles " + kHandles.string() + " --export " + (dir / "a_file" / "out.obj").string() +
                     " --export-on-exit > " + log.string() + " 2>&1");
  std::ifstream in(log);
  const std::string output((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CAPTURE(output);
  CHECK(status == 1);
  CHECK(output.find("lapis-deform: export failed: ") != std::string::npos);
  CHECK(output.find("exported") == std::string::npos);
}

TEST_CASE("deform app: transfer pairs grow from their clicks to their handle's share of the area, apart") {
  using deform_app::TransferPairing;
  const geometry::TriMesh sphere = geometry::make_icosphere(3);
  const geometry::Connectivity conn(sphere);
  const Eigen::VectorXd areas = geometry::vertex_areas(sphere, geometry::MassType::Barycentric);
  const double total = areas.sum(), largest = areas.maxCoeff();
  int top = 0, bottom = 0;
  sphere.V.col(2).maxCoeff(&top);
  sphere.V.col(2).minCoeff(&bottom);
  const auto regions = deform_app::grow_regions(sphere.V, conn, areas, {top, bottom}, {0.3, 0.1});
  REQUIRE(regions.size() == 2);
  std::vector<int> owner(static_cast<size_t>(sphere.num_vertices()), -1);
  for (int k = 0; k < 2; ++k) {
    const auto& r = regions[static_cast<size_t>(k)];
    CHECK(std::binary_search(r.begin(), r.end(), k == 0 ? top : bottom));
    double a = 0;
    for (int v : r) {
      CHECK(owner[static_cast<size_t>(v)] == -1);  // disjoint
      owner[static_cast<size_t>(v)] = k;
      a += areas[v];
    }
    const double want = k == 0 ? 0.3 : 0.1;
    CHECK(a / total >= want);
    CHECK(a / total < want + largest / total + 1e-12);
  }
  // Nearest first: the top region is a cap, every vertex in it higher than every vertex outside
  // it on its side (up to one ring's unevenness).
  double lowest_in = 1, highest_out = -1;
  for (int v = 0; v < sphere.num_vertices(); ++v) {
    if (owner[static_cast<size_t>(v)] == 0)
      lowest_in = std::min(lowest_in, sphere.V(v, 2));
    else
      highest_out = std::max(highest_out, sphere.V(v, 2));
  }
  CHECK(lowest_in > highest_out - 0.2);

  // A pairing for a source with a fixed region and two handles.
  mesh_deform::Selection source;
  for (int v = 0; v < sphere.num_vertices(); ++v)
    if (sphere.V(v, 2) > -0.5) source.roi.push_back(v);
  std::vector<int> east_cap, west_cap;
  for (int v : source.roi) {
    if (sphere.V(v, 0) > 0.8) east_cap.push_back(v);
    if (sphere.V(v, 0) < -0.8) west_cap.push_back(v);
  }
  source.region_handles = {east_cap, west_cap};
  TransferPairing pairing(geometry::loop_subdivide(sphere, 1));
  pairing.set_source(sphere, conn, source, {0, 2});
  REQUIRE(pairing.slots().size() == 3);
  CHECK(pairing.slots()[0].label == -1);
  CHECK(pairing.slots()[2].name == "handle 2");
  CHECK(!pairing.complete());
  CHECK_THROWS_AS(pairing.selection(), InvalidArgument);
  const geometry::Vertices& T = pairing.target().V;
  int east = 0, west = 0, south = 0;
  T.col(0).maxCoeff(&east);
  T.col(0).minCoeff(&west);
  T.col(2).minCoeff(&south);
  pairing.place(0, south);
  pairing.place(1, east);
  pairing.place(2, south);  // the fixed region's point: refused
  CHECK(!pairing.slots()[2].problem.empty());
  CHECK(!pairing.complete());
  pairing.place(2, west);
  REQUIRE(pairing.complete());
  const mesh_deform::Selection target = pairing.selection();
  // The deformer's rules hold: handles inside the ROI, the fixed region its complement.
  CHECK_NOTHROW(mesh_deform::make_layout(target, pairing.target().num_vertices(), "test"));
  CHECK(target.roi.size() + pairing.slots()[0].region.size() == static_cast<size_t>(T.rows()));
  // Repainting the source keeps the clicks and regrows for the new shares.
  const std::uint64_t revision = pairing.revision();
  std::erase_if(source.region_handles[1], [&](int v) { return sphere.V(v, 0) > -0.9; });
  pairing.set_source(sphere, conn, source, {0, 2});
  CHECK(pairing.complete());
  CHECK(pairing.revision() > revision);
  CHECK(pairing.slots()[2].seeds == std::vector<int>{west});

  // A region in two parts (both caps) takes two clicks, each growing to its part's share.
  std::vector<int> caps;
  for (int v = 0; v < sphere.num_vertices(); ++v)
    if (std::abs(sphere.V(v, 2)) > 0.9) caps.push_back(v);
  const std::vector<double> parts = deform_app::part_areas(conn, areas, caps);
  REQUIRE(parts.size() == 2);
  CHECK(parts[0] == doctest::Approx(parts[1]).epsilon(0.05));
  source.roi = complement(caps, sphere.num_vertices());
  source.region_handles = {east_cap};
  pairing.set_source(sphere, conn, source, {0});
  REQUIRE(pairing.slots()[0].parts() == 2);
  int north = 0;
  T.col(2).maxCoeff(&north);
  pairing.clear(0);
  pairing.place(0, north);
  CHECK(!pairing.complete());
  CHECK(pairing.next_unplaced() == 0);
  pairing.place(0, south);
  pairing.place(1, east);
  REQUIRE(pairing.complete());
  const auto& fixed = pairing.slots()[0].region;
  CHECK(std::binary_search(fixed.begin(), fixed.end(), north));
  CHECK(std::binary_search(fixed.begin(), fixed.end(), south));
}

namespace {

// A pixel where a click on the drawn target picks one of `wanted` (its vertices), trying them
// nearest to their centroid first, clear of the panels; none when no such vertex shows.
std::optional<Eigen::Vector2d> click_on(const geometry::TriMesh& shown, const geometry::CameraMatrices& cam,
                                        const std::vector<int>& wanted, int width, int height) {
  const geometry::Bvh bvh(shown);
  std::vector<char> in(static_cast<size_t>(shown.num_vertices()), 0);
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int v : wanted) in[static_cast<size_t>(v)] = 1, c += shown.V.row(v).transpose();
  c /= static_cast<double>(wanted.size());
  std::vector<int> order = wanted;
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return (shown.V.row(a).transpose() - c).norm() < (shown.V.row(b).transpose() - c).norm();
  });
  for (int v : order) {
    const Eigen::Vector2d p = rounded(pixel(cam, shown.V.row(v).transpose()));
    if (p.x() < 360 || p.x() > width - 350 || p.y() < 40 || p.y() > height - 40) continue;
    const auto hit = viewer::pick(bvh, cam, p.x(), p.y());
    if (hit && in[static_cast<size_t>(viewer::nearest_corner(shown, *hit))]) return p;
  }
  return std::nullopt;
}

// The connected parts of `vertices`, largest first.
std::vector<std::vector<int>> parts_of(const geometry::TriMesh& mesh, const std::vector<int>& vertices) {
  const geometry::Connectivity conn(mesh);
  std::vector<char> in(static_cast<size_t>(mesh.num_vertices()), 0);
  for (int v : vertices) in[static_cast<size_t>(v)] = 1;
  std::vector<std::vector<int>> parts;
  for (int start : vertices) {
    if (in[static_cast<size_t>(start)] != 1) continue;
    std::vector<int> part{start}, pending{start};
    in[static_cast<size_t>(start)] = 2;
    while (!pending.empty()) {
      const int v = pending.back();
      pending.pop_back();
      for (int w : conn.vertex_neighbors(v))
        if (in[static_cast<size_t>(w)] == 1) in[static_cast<size_t>(w)] = 2, part.push_back(w), pending.push_back(w);
    }
    parts.push_back(std::move(part));
  }
  std::sort(parts.begin(), parts.end(), [](const auto& a, const auto& b) { return a.size() > b.size(); });
  return parts;
}

Eigen::Vector3d mean_displacement(const geometry::Vertices& from, const geometry::Vertices& to,
                                  const std::vector<int>& vertices) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int v : vertices) sum += (to.row(v) - from.row(v)).transpose();
  return sum / static_cast<double>(vertices.size());
}

}  // namespace

TEST_CASE("apps: deform app — a transfer target paired by clicks follows the drag; its export equals lapis transfer") {
  const fs::path dir = scratch_dir();
  const geometry::TriMesh mesh = geometry::read_mesh(kMesh);
  // The target: the camel Loop-subdivided once, whose first #V vertices are the camel's, smoothed.
  const geometry::TriMesh target = geometry::loop_subdivide(mesh, 1);
  const fs::path target_path = dir / "camel_loop1.obj";
  geometry::write_mesh(target_path, target);
  const mesh_deform::Drag saved = mesh_deform::read_handles(kHandles);
  const std::vector<int>& handle = saved.selection.region_handles.at(0);
  const std::vector<int> fixed = complement(mesh_deform::read_roi(kRoi), mesh.num_vertices());
  const std::vector<std::vector<int>> feet = parts_of(mesh, fixed);  // the fixed region: the four feet
  REQUIRE(feet.size() == 4);

  // What the app shows first: the camel and the target beside it, framed together.
  constexpr int width = 1200, height = 800;
  const deform_app::Placement place = deform_app::place_beside(mesh, target);
  const geometry::TriMesh shown_target{place.apply(target.V), target.F};
  geometry::Vertices both(mesh.V.rows() + target.V.rows(), 3);
  both << mesh.V, shown_target.V;
  const geometry::CameraMatrices cam = initial_camera(both, width, height);
  std::vector<Eigen::Vector2d> clicks;
  for (const std::vector<int>& part : feet) {
    const auto p = click_on(shown_target, cam, part, width, height);
    REQUIRE(p);
    clicks.push_back(*p);
  }
  const auto handle_click = click_on(shown_target, cam, handle, width, height);
  REQUIRE(handle_click);
  clicks.push_back(*handle_click);
  const PlannedDrag drag = plan_drag(mesh, handle, cam, width, height);
  REQUIRE(drag.axis >= 0);

  // Click each foot, then the head (the pair tool is on once a target is open), drag the
  // gizmo, export.
  std::string actions;
  for (const Eigen::Vector2d& p : clicks)
    actions += "mark; xdotool mousemove --window $w " + xy(p) +
               " sleep 0.1 click 1; wait_handled 0 2 || { kill $app; exit 5; }\n";
  actions += "mark; xdotool mousemove --window $w " + xy(drag.from) + " sleep 0.1 mousedown 1";
  for (int k = 1; k <= 20; ++k)
    actions += " mousemove --window $w " + xy(drag.from + (drag.to - drag.from) * (k / 20.0)) + " sleep 0.03";
  actions += " mouseup 1; wait_handled 0 2 || { kill $app; exit 5; }\nxdotool key --window $w ctrl+e";
  const fs::path out = dir / "transferred.obj";
  REQUIRE(run_window("--mesh " + kMesh.string() + " --roi " + kRoi.string() + " --handles " + kHandles.string() +
                         " --method implicit --transfer-target " + target_path.string() + " --export " + out.string(),
                     actions, dir / "transferred.deform.json", " --size 1200x800") == 0);
  std::ifstream report(dir / "transferred.deform.json");
  const auto j = nlohmann::json::parse(report);
  REQUIRE(j.contains("transfer"));
  const geometry::TriMesh moved = geometry::read_mesh(out);
  const geometry::TriMesh moved_target = geometry::read_mesh(dir / "transferred.target.obj");
  REQUIRE(moved_target.V.rows() == target.V.rows());

  // `lapis transfer` on the files the app wrote gives the same target.
  const fs::path cli_out = dir / "cli_target.obj";
  REQUIRE(run(kCli + " transfer --source " + kMesh.string() + " --source-deformed " + out.string() +
              " --source-handles " + (dir / "transferred.handles.json").string() + " --source-roi " +
              (dir / "transferred.roi.txt").string() + " --target " + target_path.string() + " --target-handles " +
              (dir / "transferred.target.handles.json").string() + " --target-roi " +
              (dir / "transferred.target.roi.txt").string() + " --out " + cli_out.string() + " > /dev/null") == 0);
  CHECK(max_difference(geometry::read_mesh(cli_out).V, moved_target.V) < 1e-9);

  // The target moved as the camel did: its handle like the camel's, its fixed region not, and
  // the camel's own vertices in it (Loop keeps them first) by about the same amount.
  const mesh_deform::Drag target_handles = mesh_deform::read_handles(dir / "transferred.target.handles.json");
  const std::vector<int> target_fixed =
      complement(mesh_deform::read_roi(dir / "transferred.target.roi.txt"), target.num_vertices());
  const Eigen::Vector3d source_move = mean_displacement(mesh.V, moved.V, handle);
  const Eigen::Vector3d target_move =
      mean_displacement(target.V, moved_target.V, target_handles.selection.region_handles.at(0));
  CAPTURE(source_move.transpose());
  CAPTURE(target_move.transpose());
  REQUIRE(source_move.norm() > 0);
  CHECK((target_move - source_move).norm() < 0.25 * source_move.norm());
  double fixed_moved = 0, shared = 0;
  for (int v : target_fixed) fixed_moved = std::max(fixed_moved, (moved_target.V.row(v) - target.V.row(v)).norm());
  for (int v = 0; v < mesh.num_vertices(); ++v)
    shared += ((moved_target.V.row(v) - target.V.row(v)) - (moved.V.row(v) - mesh.V.row(v))).norm();
  shared /= mesh.num_vertices();
  CAPTURE(fixed_moved);
  CAPTURE(shared);
  // Eq. 12 holds one vertex, not the fixed region, and the clicked regions are not the
  // camel's own: measured 23% and 14% of the handle's move.
  CHECK(fixed_moved < 0.4 * source_move.norm());
  CHECK(shared < 0.25 * source_move.norm());
}

TEST_CASE("apps: deform app — ARAP iterates to convergence once posed, and toggling the colours changes nothing") {
  const fs::path dir = scratch_dir();
  const geometry::TriMesh mesh = geometry::read_mesh(kMesh);
  mesh_deform::Selection selection = mesh_deform::read_handles(kHandles).selection;
  // The head turned 35 degrees about x and lifted: a pose ten iterations leave far from rest.
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int v : selection.region_handles.at(0)) c += mesh.V.row(v).transpose();
  c /= static_cast<double>(selection.region_handles[0].size());
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.6, Eigen::Vector3d::UnitX()).toRotationMatrix();
  T.topLeftCorner<3, 3>() = R;
  T.topRightCorner<3, 1>() = c - R * c + Eigen::Vector3d(0, 0.1, 0);
  const fs::path pose = dir / "pose.handles.json";
  mesh_deform::write_handles(pose, selection, {mesh_deform::HandleTransforms{{T}, {}}});

  // Export once it settles, keep a copy, toggle the colours twice, export again.
  const std::string d = dir.string();
  const std::string actions =
      "xdotool key --window $w ctrl+e\n"
      "for i in $(seq 1 2400); do [ -e " +
      d +
      "/arap.deform.json ] && break; sleep 0.1; done\n"
      "mkdir -p " +
      d + "/first && cp " + d + "/arap.* " + d + "/first/ && rm " + d +
      "/arap.deform.json\n"
      "mark; xdotool key --window $w c key --window $w c; wait_handled 4 0 || { kill $app; exit 5; }\n"
      "xdotool key --window $w ctrl+e";
  const fs::path out = dir / "arap.obj";
  REQUIRE(run_window("--mesh " + kMesh.string() + " --roi " + kRoi.string() + " --handles " + pose.string() +
                         " --method arap --export " + out.string(),
                     actions, dir / "arap.deform.json") == 0);
  const geometry::TriMesh first = geometry::read_mesh(dir / "first" / "arap.obj"), second = geometry::read_mesh(out);
  CHECK(max_difference(first.V, second.V) == 0);  // the colours did not solve again
  std::ifstream a(dir / "first" / "arap.deform.json"), b(dir / "arap.deform.json");
  const auto ja = nlohmann::json::parse(a), jb = nlohmann::json::parse(b);
  CHECK(ja["frames"] == jb["frames"]);
  CHECK(ja["frames"].get<int>() > 2);  // rounds after the first solve

  // The rounds lowered the energy past one frame's ten iterations, toward a long run's.
  auto cli_arap = [&](int iterations, const fs::path& handles) {
    const fs::path o = dir / ("cli_" + std::to_string(iterations) + ".obj");
    REQUIRE(run(kCli + " deform --mesh " + kMesh.string() + " --roi " + kRoi.string() + " --handles " +
                handles.string() + " --method arap --iterations " + std::to_string(iterations) + " --out " +
                o.string() + " > /dev/null") == 0);
    return geometry::read_mesh(o);
  };
  const double app = mesh_deform::distortion(mesh, second.V).arap_energy;
  const double ten = mesh_deform::distortion(mesh, cli_arap(10, pose).V).arap_energy;
  const double long_run = mesh_deform::distortion(mesh, cli_arap(2000, pose).V).arap_energy;
  CAPTURE(app);
  CAPTURE(ten);
  CAPTURE(long_run);
  CHECK(app < 0.9 * ten);
  CHECK(app < long_run * 1.01);
  // The frames it recorded replay to the same mesh.
  const geometry::TriMesh replayed = cli_arap(10, dir / "arap.handles.json");
  CHECK(max_difference(replayed.V, second.V) < 1e-9);
}

namespace {

// Selection tools, replayed headless on the camel from its first view: the selection files
// Ctrl+S writes (a fresh pair per run) and what the app logged.
struct ToolRun {
  std::vector<int> roi, handle;
  std::string log;
};

ToolRun run_tools(const std::string& name, EventScript script, const fs::path& mesh = kMesh) {
  const fs::path dir = scratch_dir() / name;
  fs::create_directories(dir);
  script.key(EventScript::kKeyS, EventScript::kCtrl);
  script.frame += 5;
  script.log.width = kWidth, script.log.height = kHeight;
  script.log.save(dir / "events.json");
  const fs::path roi = dir / "sel.roi.txt", handles = dir / "sel.handles.json", log = dir / "log.txt";
  const int status = run_under_xvfb(kApp + " --headless" + kSize + " --mesh " + mesh.string() + " --roi " +
                                    roi.string() + " --handles " + handles.string() + " --replay " +
                                    (dir / "events.json").string() + " --exit-after-replay 2> " + log.string());
  REQUIRE(status == 0);
  std::ifstream in(log);
  ToolRun r;
  r.log.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  REQUIRE_MESSAGE(fs::exists(handles), r.log);
  const mesh_deform::Drag saved = mesh_deform::read_handles(handles);
  r.roi = mesh_deform::read_roi(roi);
  if (!saved.selection.region_handles.empty()) r.handle = saved.selection.region_handles[0];
  return r;
}

constexpr int kKeyX = 88, kKeyK = 75, kKeyG = 71, kKeyM = 77, kKey1 = 49, kKeyLeftBracket = 91, kKeyRightBracket = 93;

// A horizontal stroke through the middle of the camel's body as the first view shows it.
std::vector<Eigen::Vector2d> body_stroke(const geometry::TriMesh& mesh, const geometry::CameraMatrices& cam,
                                         double dy = 0) {
  const Eigen::Vector2d mid = pixel(cam, mesh.V.colwise().mean().transpose()) + Eigen::Vector2d(0, dy);
  std::vector<Eigen::Vector2d> stroke;
  for (int k = -6; k <= 6; ++k) stroke.push_back(rounded(mid + Eigen::Vector2d(10.0 * k, 0)));
  return stroke;
}

// The vertices the first view shows (facing the camera, not hidden).
std::vector<char> visible_in(const geometry::TriMesh& mesh, const geometry::CameraMatrices& cam) {
  const geometry::Bvh bvh(mesh);
  const std::vector<Eigen::Vector2d> screen{{0, 0}, {kWidth, 0}, {kWidth, kHeight}, {0, kHeight}};
  std::vector<char> seen(static_cast<size_t>(mesh.num_vertices()), 0);
  for (int v : viewer::lasso_vertices(mesh, bvh, cam, screen)) seen[static_cast<size_t>(v)] = 1;
  return seen;
}

}  // namespace

TEST_CASE("apps: deform app — the x-ray brush paints the back the plain brush leaves") {
  const geometry::TriMesh mesh = geometry::read_mesh(kMesh);
  const geometry::CameraMatrices cam = initial_camera(mesh);
  const std::vector<char> visible = visible_in(mesh, cam);
  auto hidden = [&](const std::vector<int>& set) {
    return std::count_if(set.begin(), set.end(), [&](int v) { return !visible[static_cast<size_t>(v)]; });
  };
  EventScript plain, xray;
  for (EventScript* s : {&plain, &xray}) {
    if (s == &xray) s->key(kKeyX);
    s->key(EventScript::kKeyB);
    s->key(EventScript::kKey3);
    s->drag(body_stroke(mesh, cam));
  }
  const ToolRun a = run_tools("plain", plain), b = run_tools("xray", xray);
  MESSAGE("handle: plain brush " << a.handle.size() << " vertices (" << hidden(a.handle) << " hidden), x-ray "
                                 << b.handle.size() << " (" << hidden(b.handle) << " hidden)");
  REQUIRE(a.handle.size() > 20);
  CHECK(hidden(a.handle) <= static_cast<long>(a.handle.size()) / 20);  // the sheet under the cursor
  CHECK(std::includes(b.handle.begin(), b.handle.end(), a.handle.begin(), a.handle.end()));
  CHECK(hidden(b.handle) > static_cast<long>(a.handle.size()) / 2);  // and the far side
}

TEST_CASE("apps: deform app — Ctrl+M adds the mirror image of the target; again, nothing changes") {
  const fs::path dir = scratch_dir();
  const geometry::TriMesh sphere = geometry::make_icosphere(4);  // symmetric about x = 0 (auto: x)
  const fs::path path = dir / "sphere.obj";
  geometry::write_mesh(path, sphere);
  const geometry::CameraMatrices cam = initial_camera(sphere);
  const Eigen::Vector2d centre = pixel(cam, Eigen::Vector3d(0, 0, 0));
  const Eigen::Vector2d right = pixel(cam, Eigen::Vector3d(1, 0, 0));
  const double r = (right - centre).norm();
  const int sign = right.x() > centre.x() ? -1 : 1;  // the stroke on the side of x < 0
  std::vector<Eigen::Vector2d> stroke;
  for (int k = 0; k <= 4; ++k) stroke.push_back(rounded(centre + Eigen::Vector2d(sign * 0.5 * r, (k - 2) * 0.1 * r)));
  EventScript once, twice;
  for (EventScript* s : {&once, &twice}) {
    s->key(EventScript::kKeyB);
    s->key(EventScript::kKey3);
    s->drag(stroke);
    s->key(kKeyM, EventScript::kCtrl);
    if (s == &twice) s->key(kKeyM, EventScript::kCtrl);
  }
  EventScript painted;
  painted.key(EventScript::kKeyB);
  painted.key(EventScript::kKey3);
  painted.drag(stroke);
  const ToolRun p = run_tools("stroke", painted, path), a = run_tools("mirror", once, path),
                b = run_tools("mirror_twice", twice, path);
  REQUIRE(p.handle.size() > 10);
  for (int v : p.handle) CHECK(sphere.V(v, 0) < 0);
  // The stroke and its image: the image of each stroke vertex (x -> -x) is in the handle.
  CHECK(a.handle.size() == 2 * p.handle.size());
  const geometry::MirroredVertices image =
      geometry::mirror_vertices(sphere.V, p.handle, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), 1e-6);
  CHECK(image.unmatched.empty());
  std::vector<int> both = p.handle;
  both.insert(both.end(), image.vertices.begin(), image.vertices.end());
  std::sort(both.begin(), both.end());
  CHECK(a.handle == both);
  CHECK(a.log.find("mirror across x (auto): " + std::to_string(p.handle.size()) + " of " +
                   std::to_string(p.handle.size()) + " vertices matched, 0 without") != std::string::npos);
  CHECK(b.handle == a.handle);  // a symmetric selection mirrors onto itself
}

TEST_CASE("apps: deform app — a connected click takes exactly the clicked component; a geodesic click a disc") {
  const fs::path dir = scratch_dir();
  // A sphere and a torus beside it, one mesh of two components.
  const geometry::TriMesh sphere = geometry::make_icosphere(3), torus = geometry::make_torus(32, 16);
  geometry::TriMesh both;
  both.V.resize(sphere.V.rows() + torus.V.rows(), 3);
  both.V << sphere.V, torus.V.rowwise() + Eigen::RowVector3d(3.5, 0, 0);
  both.F.resize(sphere.F.rows() + torus.F.rows(), 3);
  both.F << sphere.F, torus.F.array() + static_cast<int>(sphere.V.rows());
  const fs::path two = dir / "two_parts.obj";
  geometry::write_mesh(two, both);
  const geometry::CameraMatrices cam2 = initial_camera(both);
  EventScript connected;
  connected.key(kKeyK);
  connected.key(EventScript::kKey3);
  // The torus vertex nearest the eye: in front, so the click lands on the torus.
  const Eigen::Vector3d eye = geometry::eye_position(cam2);
  int nearest = static_cast<int>(sphere.V.rows());
  for (int v = nearest; v < both.num_vertices(); ++v)
    if ((both.V.row(v).transpose() - eye).norm() < (both.V.row(nearest).transpose() - eye).norm()) nearest = v;
  const Eigen::Vector2d on_torus = rounded(pixel(cam2, both.V.row(nearest).transpose()));
  const geometry::Bvh bvh2(both);
  const auto torus_hit = viewer::pick(bvh2, cam2, on_torus.x(), on_torus.y());
  REQUIRE(torus_hit);
  REQUIRE(both.F(torus_hit->face, 0) >= sphere.V.rows());
  connected.drag({on_torus});
  const ToolRun r = run_tools("connected", connected, two);
  std::vector<int> torus_vertices;
  for (int v = static_cast<int>(sphere.V.rows()); v < both.num_vertices(); ++v) torus_vertices.push_back(v);
  CHECK(r.handle == torus_vertices);

  // Geodesic: a click on the camel's flank takes the vertices within 0.04 of the diagonal of the
  // clicked vertex along the surface, the same as geometry::geodesic_disc.
  const geometry::TriMesh mesh = geometry::read_mesh(kMesh);
  const geometry::CameraMatrices cam = initial_camera(mesh);
  const Eigen::Vector2d click = body_stroke(mesh, cam)[6];
  const geometry::Bvh bvh(mesh);
  const auto hit = viewer::pick(bvh, cam, click.x(), click.y());
  REQUIRE(hit);
  const int seed = viewer::nearest_corner(mesh, *hit);
  const double radius = 0.04 * (mesh.V.colwise().maxCoeff() - mesh.V.colwise().minCoeff()).norm();
  EventScript geodesic;
  geodesic.key(kKeyG);
  geodesic.key(EventScript::kKey3);
  geodesic.drag({click});
  const ToolRun g = run_tools("geodesic", geodesic);
  const std::vector<int> disc = geometry::geodesic_disc(mesh, geometry::Connectivity(mesh), seed, radius);
  CHECK(g.handle == disc);
  double farthest = 0;
  for (int v : g.handle) farthest = std::max(farthest, (mesh.V.row(v) - mesh.V.row(seed)).norm());
  CHECK(farthest <= radius + 1e-12);
  CHECK(farthest > 0.7 * radius);
  CHECK(g.handle.size() > 20);
}

TEST_CASE("apps: deform app — a handle reaching past a narrow ROI warns that the ROI's border cuts by it") {
  const geometry::TriMesh mesh = geometry::read_mesh(kMesh);
  const geometry::CameraMatrices cam = initial_camera(mesh);
  EventScript s;
  s.key(EventScript::kKeyB);
  s.key(kKey1);
  for (int k = 0; k < 3; ++k) s.key(kKeyLeftBracket);
  s.drag(body_stroke(mesh, cam));  // a narrow ROI on the visible side: everything else is fixed
  s.key(EventScript::kKey3);
  for (int k = 0; k < 3; ++k) s.key(kKeyRightBracket);
  s.drag(body_stroke(mesh, cam));  // a wider handle along it reaches into the fixed region: a warning
  const ToolRun r = run_tools("warning", s);
  // The saved selection: the handle vertices within 2 rings of the fixed region, as the warning counts them.
  REQUIRE(r.handle.size() > 20);
  std::vector<char> in_roi(static_cast<size_t>(mesh.num_vertices()), 0);
  for (int v : r.roi) in_roi[static_cast<size_t>(v)] = 1;
  const std::vector<int> near = geometry::near_region_border(geometry::Connectivity(mesh), in_roi, r.handle, 2);
  CHECK(near.size() > 10);
  CAPTURE(r.log);
  CHECK(r.log.find("lapis-deform: warning: the ROI's border cuts close to a handle: handle 0: " +
                   std::to_string(near.size()) + " of " + std::to_string(r.handle.size()) +
                   " vertices within 2 rings of the fixed region") != std::string::npos);
}

TEST_CASE("apps: deform app — quitting with unsaved edits asks: Esc stays, S saves and quits; no edits, no question") {
  const fs::path dir = scratch_dir() / "unsaved";
  fs::create_directories(dir);
  const fs::path roi = dir / "sel.roi.txt", handles = dir / "sel.handles.json", log = dir / "unsaved.log";
  fs::copy_file(kRoi, roi, fs::copy_options::overwrite_existing);
  fs::copy_file(kHandles, handles, fs::copy_options::overwrite_existing);
  const std::string app = kApp + kSize + " --mesh " + kMesh.string() + " --roi " + roi.string() + " --handles " +
                          handles.string() + " --ready-file " + (dir / "ready").string() + " 2>" + log.string() +
                          " &\n";
  // The pointer over the 3D view (keys act where it is); 2 then = grows the fixed region: an
  // edit. Ctrl+Q asks; Esc keeps the window; Ctrl+Q asks again; S saves and quits.
  const std::string body = app +
                           "app=$!\n"
                           "window lapis-deform || { kill $app; exit 3; }\n"
                           "wait_ready '[ $busy -eq 0 ]' || { kill $app; exit 4; }\n"
                           "xdotool mousemove --window $w 450 120\n"
                           "mark; xdotool key --window $w 2 key --window $w equal; wait_handled 4 0 || exit 5\n"
                           "xdotool key --window $w ctrl+q; wait_ready '[ $asking -eq 1 ]' 60 || exit 6\n"
                           "kill -0 $app || exit 7\n"
                           "xdotool key --window $w Escape; wait_ready '[ $asking -eq 0 ]' 60 || exit 8\n"
                           "kill -0 $app || exit 9\n"
                           "xdotool key --window $w ctrl+q; wait_ready '[ $asking -eq 1 ]' 60 || exit 10\n"
                           "xdotool key --window $w s; wait $app\n";
  const std::string before = text_of(roi);
  REQUIRE(run_under_xvfb(ready_script(dir / "unsaved.sh", dir / "ready", body)) == 0);
  const std::string said = text_of(log);
  CAPTURE(said);
  CHECK(said.find("lapis-deform: unsaved edits: asking before quitting") != std::string::npos);
  CHECK(said.find("lapis-deform: unsaved edits: stayed") != std::string::npos);
  CHECK(said.find("lapis-deform: unsaved edits: saved") != std::string::npos);
  // The saved ROI: the grown fixed region took a ring of it.
  const std::vector<int> saved = mesh_deform::read_roi(roi);
  CHECK(text_of(roi) != before);
  CHECK(saved.size() < mesh_deform::read_roi(kRoi).size());

  // Opened and quit at once: nothing to save, no question.
  const std::string quiet = app +
                            "app=$!\n"
                            "window lapis-deform || { kill $app; exit 3; }\n"
                            "wait_ready '[ $busy -eq 0 ]' || { kill $app; exit 4; }\n"
                            "xdotool key --window $w ctrl+q; wait $app\n";
  REQUIRE(run_under_xvfb(ready_script(dir / "quiet.sh", dir / "ready", quiet)) == 0);
  CHECK(text_of(log).find("unsaved edits") == std::string::npos);
}

TEST_CASE(
    "apps: deform app — a mesh's files are its own, next to it: its selection opens with it, Ctrl+P and Ctrl+S "
    "write beside it") {
  const fs::path dir = scratch_dir() / "beside";
  fs::create_directories(dir);
  const fs::path mesh = dir / "camel.off";
  fs::copy_file(kMesh, mesh, fs::copy_options::overwrite_existing);
  fs::copy_file(kRoi, dir / "camel.roi.txt", fs::copy_options::overwrite_existing);
  fs::copy_file(kHandles, dir / "camel.handles.json", fs::copy_options::overwrite_existing);
  fs::remove(dir / "camel.screenshot.png");
  EventScript s;
  s.key(EventScript::kKey2);
  s.key(EventScript::kKeyEqual);  // an edit: the fixed region grows a ring
  s.key(EventScript::kKeyS, EventScript::kCtrl);
  s.key(80, EventScript::kCtrl);  // Ctrl+P
  s.frame += 5;
  s.log.width = kWidth, s.log.height = kHeight;
  s.log.save(dir / "events.json");
  const fs::path log = dir / "log.txt";
  // No file flags: the app finds the mesh's own.
  REQUIRE(run_under_xvfb(kApp + " --headless" + kSize + " " + mesh.string() + " --replay " +
                         (dir / "events.json").string() + " --exit-after-replay 2> " + log.string()) == 0);
  const std::string said = text_of(log);
  CAPTURE(said);
  CHECK(said.find("opened " + (dir / "camel.roi.txt").string() + " and " + (dir / "camel.handles.json").string()) !=
        std::string::npos);
  CHECK(said.find("saved " + (dir / "camel.roi.txt").string()) != std::string::npos);
  CHECK(fs::exists(dir / "camel.screenshot.png"));
  // The saved selection is the opened one with the fixed region grown: the ROI lost a ring.
  CHECK(mesh_deform::read_roi(dir / "camel.roi.txt").size() < mesh_deform::read_roi(kRoi).size());
}

namespace {

// Pixels that differ between two screenshots inside the square of half-size `r` around `c`.
int differing_pixels(const viewer::Image& a, const viewer::Image& b, const Eigen::Vector2i& c, int r) {
  REQUIRE(a.width == b.width);
  REQUIRE(a.height == b.height);
  int n = 0;
  for (int y = std::max(0, c.y() - r); y < std::min(a.height, c.y() + r); ++y)
    for (int x = std::max(0, c.x() - r); x < std::min(a.width, c.x() + r); ++x) {
      const size_t i = 4 * (static_cast<size_t>(y) * static_cast<size_t>(a.width) + static_cast<size_t>(x));
      n += a.rgba[i] != b.rgba[i] || a.rgba[i + 1] != b.rgba[i + 1] || a.rgba[i + 2] != b.rgba[i + 2];
    }
  return n;
}

}  // namespace

TEST_CASE("apps: deform app — the brush circle is drawn over the mesh, not over the panels") {
  const fs::path dir = scratch_dir() / "brush_circle";
  fs::create_directories(dir);
  // The pointer over the Selection panel (right column) and over the camel (the middle), with
  // the move tool and with the brush (B).
  const Eigen::Vector2i panel(kWidth - 180, 250), body(kWidth / 2, kHeight / 2 + 40);
  auto shot = [&](const std::string& name, bool brush, const Eigen::Vector2i& at) {
    EventScript s;
    if (brush) s.key(EventScript::kKeyB);
    s.move(at.cast<double>());
    s.move(at.cast<double>() + Eigen::Vector2d(1, 0));
    s.move(at.cast<double>());
    s.log.width = kWidth, s.log.height = kHeight;
    s.log.save(dir / (name + ".json"));
    const fs::path png = dir / (name + ".png");
    REQUIRE(run_under_xvfb(kApp + " --headless" + kSize + " --mesh " + kMesh.string() + " --roi " + kRoi.string() +
                           " --handles " + kHandles.string() + " --replay " + (dir / (name + ".json")).string() +
                           " --exit-after-replay --screenshot " + png.string()) == 0);
    return viewer::read_png(png);
  };
  const int r = 40;  // the default brush is 24 px
  // Over the mesh the circle shows; over the panel nothing differs from the move tool.
  CHECK(differing_pixels(shot("body_move", false, body), shot("body_brush", true, body), body, r) > 50);
  const viewer::Image panel_move = shot("panel_move", false, panel), panel_brush = shot("panel_brush", true, panel);
  // (The panel's tool buttons, above the square, show the other tool.)
  CHECK(differing_pixels(panel_move, panel_brush, panel, r) == 0);
}
