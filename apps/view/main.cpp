// lapis-view: open a mesh (OBJ/OFF/PLY/STL) in the Lapis viewer shell. The smallest app on
// the shell, and the one its tests drive.
//   lapis-view MESH [--headless] [--screenshot OUT.png] [--replay EVENTS] [--record EVENTS]
#include <imgui.h>

#include <cstdio>

#include "lapis/core/error.h"
#include "lapis/geometry/io.h"
#include "lapis/viewer/viewer.h"

namespace {

class MeshView final : public lapis::viewer::ViewerApp {
 public:
  explicit MeshView(lapis::geometry::TriMesh mesh) : mesh_(std::move(mesh)) {}

  void on_start(lapis::viewer::Viewer& v) override {
    v.scene().meshes["mesh"].mesh = mesh_;
    v.frame_scene();
  }
  void on_gui(lapis::viewer::Viewer& v) override {
    v.overlay(std::to_string(mesh_.V.rows()) + " vertices, " + std::to_string(mesh_.F.rows()) + " faces");
  }

 private:
  lapis::geometry::TriMesh mesh_;
};

}  // namespace

int main(int argc, char** argv) {
  try {
    lapis::viewer::ViewerOptions options;
    options.title = "lapis-view";
    const auto rest = lapis::viewer::parse_viewer_flags(argc, argv, options);
    if (rest.size() != 1 || rest[0] == "--help") {
      std::printf(
          "usage: lapis-view MESH [--headless] [--screenshot OUT.png] [--replay EVENTS] "
          "[--record EVENTS] [--exit-after-replay] [--benchmark OUT.json] [--ready-file F] [--size WxH]\n");
      return rest.size() == 1 ? 0 : 2;
    }
    MeshView app(lapis::geometry::read_mesh(rest[0]));
    lapis::viewer::Viewer viewer(options);
    return viewer.run(app);
  } catch (const lapis::Error& e) {
    std::fprintf(stderr, "lapis-view: %s\n", e.what());
    return 1;
  }
}
