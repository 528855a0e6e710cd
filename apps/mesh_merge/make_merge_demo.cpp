// Generates assets/events/merge_demo.json, the input `scripts/demo merge` replays: on preset 2
// (the devil's head onto the man) it pans the necks into the middle of the free view, zooms in,
// pairs the two neck loops, sets one key correspondence and merges. The clicks are where the
// keys project in lapis-merge's first view after that pan and zoom, computed with the app's own
// camera, so the file stays right when the view or the meshes change: re-run it then.
//   lapis_make_merge_demo <source dir>
// The key is the +x-most vertex of each neck loop: the side of the neck facing the camera (so
// the click hits it) and the same side on both necks, so the head keeps facing the body's way.
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "bundled_meshes.h"
#include "first_view.h"
#include "lapis/core/atomic_file.h"
#include "lapis/geometry/connectivity.h"
#include "lapis/mesh_merge/merge_setup.h"

using namespace lapis;

namespace {

constexpr int kWidth = 1200, kHeight = 800, kZoomSteps = 14;

int max_x_vertex(const geometry::TriMesh& m) {
  const geometry::Connectivity conn(m);
  const auto& loop = conn.boundary_loops().at(0);
  return *std::max_element(loop.begin(), loop.end(), [&](int a, int b) { return m.V(a, 0) < m.V(b, 0); });
}

struct Events {
  nlohmann::json list = nlohmann::json::array();
  int frame = 1;
  double time = 0.5;
  void next(int frames = 1) { frame += frames, time += 0.1 * frames; }
  void move(const Eigen::Vector2d& p) {
    list.push_back({{"type", "move"}, {"frame", frame}, {"time", time}, {"x", p.x()}, {"y", p.y()}});
  }
  void button(int b, int action, const Eigen::Vector2d& p) {
    list.push_back({{"type", "button"},
                    {"frame", frame},
                    {"time", time},
                    {"button", b},
                    {"action", action},
                    {"mods", 0},
                    {"x", p.x()},
                    {"y", p.y()}});
  }
  void click(const Eigen::Vector2d& p) { move(p), next(), button(0, 1, p), button(0, 0, p), next(3); }
  void key(int k, int codepoint) {
    list.push_back({{"type", "key"}, {"frame", frame}, {"time", time}, {"key", k}, {"action", 1}, {"mods", 0}});
    list.push_back({{"type", "char"}, {"frame", frame}, {"time", time}, {"codepoint", codepoint}});
    list.push_back({{"type", "key"}, {"frame", frame}, {"time", time}, {"key", k}, {"action", 0}, {"mods", 0}});
    next();
  }
};

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: lapis_make_merge_demo <source dir>\n");
    return 2;
  }
  try {
    const merge_app::MeshPair meshes = merge_app::load_preset_meshes(2, std::filesystem::path(argv[1]) / "assets");
    mesh_merge::MergeSetup setup;
    setup.source = meshes.source;
    setup.target = meshes.target;
    setup.placement = mesh_merge::suggest_placement(*meshes.source, *meshes.target);
    const geometry::TriMesh source = mesh_merge::placed_source(setup);
    const geometry::TriMesh& target = *meshes.target;
    viewer::OrbitCamera camera = merge_app::first_view_camera(source, target, kWidth, kHeight);
    const Eigen::Vector3d s = source.V.row(max_x_vertex(source)).transpose();
    const Eigen::Vector3d t = target.V.row(max_x_vertex(target)).transpose();
    auto pixel = [](const viewer::OrbitCamera& c, const Eigen::Vector3d& p) -> Eigen::Vector2d {
      return geometry::project(c.matrices(kWidth, kHeight), p).head<2>();
    };
    // A middle-drag from the necks to where, once zoomed, they sit mid-way across the free view.
    const Eigen::Vector2d from = pixel(camera, 0.5 * (s + t)).array().round();
    const Eigen::Vector2d goal(0.5 * (kWidth - merge_app::kPanelWidth), 0.5 * kHeight);
    Eigen::Vector2d to = goal;
    for (int i = 0; i < 5; ++i) {
      viewer::OrbitCamera c = camera;
      c.pan(to.x() - from.x(), to.y() - from.y(), kHeight);
      c.zoom(kZoomSteps);
      // Zooming scales the picture about the view's centre by 1 / 0.9^steps: a Newton step.
      to += (goal - pixel(c, 0.5 * (s + t))) * std::pow(0.9, kZoomSteps);
    }
    to = to.array().round();
    Events e;
    e.move(from), e.next(), e.button(2, 1, from);
    for (int k = 1; k <= 10; ++k) {
      e.next();
      e.move(from + (to - from) * k / 10.0);
    }
    e.button(2, 0, to), e.next(2);
    camera.pan(to.x() - from.x(), to.y() - from.y(), kHeight);
    for (int k = 0; k < kZoomSteps; ++k) {
      e.list.push_back({{"type", "scroll"}, {"frame", e.frame}, {"time", e.time}, {"x", 0.0}, {"y", 1.0}});
      e.next();
    }
    camera.zoom(kZoomSteps);
    const Eigen::Vector2d sp = pixel(camera, s).array().round(), tp = pixel(camera, t).array().round();
    // Tool 1 pairs the loops clicked on each mesh, then the app switches to tool 2, keys.
    e.click(sp), e.click(tp), e.click(sp), e.click(tp);
    e.key(77, 'm');  // M: merge
    const nlohmann::json out{
        {"format", "lapis-events"}, {"version", 1}, {"width", kWidth}, {"height", kHeight}, {"events", e.list}};
    const auto path = std::filesystem::path(argv[1]) / "assets/events/merge_demo.json";
    lapis::core::write_file_atomically(path, [&](std::ostream& o) { o << out.dump(1) << "\n"; });
    std::printf("%s: key pixels source (%.0f, %.0f), target (%.0f, %.0f)\n", path.c_str(), sp.x(), sp.y(), tp.x(),
                tp.y());
  } catch (const std::exception& ex) {
    std::fprintf(stderr, "lapis_make_merge_demo: error: %s\n", ex.what());
    return 1;
  }
  return 0;
}
