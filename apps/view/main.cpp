// lapis-view: open a mesh (OBJ/OFF/PLY/STL) in the Lapis viewer shell. The smallest app on
// the shell, and the one its tests drive.
//   lapis-view MESH [--headless] [--screenshot OUT.png] [--replay EVENTS] [--record EVENTS]
#include <imgui.h>

#include <memory>

#include "lapis/core/error.h"
#include "lapis/geometry/io.h"
#include "lapis/viewer/app_main.h"

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

constexpr const char* kUsage =
    "usage: lapis-view MESH [--headless] [--screenshot OUT.png] [--replay EVENTS] [--record EVENTS]\n"
    "                  [--exit-after-replay] [--benchmark OUT.json] [--ready-file F] [--size WxH]\n";

}  // namespace

int main(int argc, char** argv) {
  return lapis::viewer::app_main(argc, argv, "lapis-view", kUsage,
                                 [](std::vector<std::string> rest) -> std::unique_ptr<lapis::viewer::ViewerApp> {
                                   if (rest.size() != 1) throw lapis::UsageError("expects one MESH");
                                   return std::make_unique<MeshView>(lapis::geometry::read_mesh(rest[0]));
                                 });
}
