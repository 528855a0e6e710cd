#include "bundled_meshes.h"

#include <algorithm>

#include "lapis/core/error.h"
#include "lapis/geometry/io.h"
#include "lapis/mesh_merge/cut.h"

namespace lapis::merge_app {

namespace fs = std::filesystem;

std::vector<BundledMesh> bundled_meshes(const fs::path& asset_dir) {
  std::vector<BundledMesh> out;
  for (const char* dir : {"merge", "external"}) {
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(asset_dir / dir, ec)) {
      const std::string ext = e.path().extension().string();
      if (ext == ".obj" || ext == ".off" || ext == ".ply" || ext == ".stl")
        out.push_back({std::string(dir) + "/" + e.path().filename().string(), e.path()});
    }
  }
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.label < b.label; });
  return out;
}

const std::vector<std::string>& preset_names() {
  static const std::vector<std::string> names{
      "dome onto neck (merge/)",
      "placed dome onto neck (merge/, for dependent mode)",
      "devil's head onto the man (external/, cut by planes)",
  };
  return names;
}

namespace {

geometry::TriMesh z_up_to_y_up(geometry::TriMesh m) {
  const Eigen::VectorXd y = m.V.col(1);
  m.V.col(1) = m.V.col(2);
  m.V.col(2) = -y;
  return m;
}

}  // namespace

MeshPair load_preset_meshes(int preset, const fs::path& asset_dir) {
  auto shared = [](geometry::TriMesh m) { return std::make_shared<const geometry::TriMesh>(std::move(m)); };
  const fs::path merge = asset_dir / "merge", external = asset_dir / "external";
  switch (preset) {
    case 0:
      return {shared(geometry::read_mesh(merge / "dome.obj")), shared(geometry::read_mesh(merge / "neck.obj")),
              "dome.obj", "neck.obj", true};
    case 1:
      return {shared(geometry::read_mesh(merge / "dome_placed.obj")), shared(geometry::read_mesh(merge / "neck.obj")),
              "dome_placed.obj", "neck.obj", false};
    case 2: {
      // The planes of the module's real-mesh test: the bust's head and neck above z = -14 (a
      // round neck rim like the man's; at z = -8 the cut runs under the chin, the rim is half as
      // deep again as wide and the merged head turns aside), the bust 40 units tall,
      // the man (1 unit tall) below his neck at z = 0.36.
      const auto devil =
          mesh_merge::cut_by_plane(geometry::read_mesh(external / "mannequin-devil.off"), {0, 0, -14.0}, {0, 0, 1});
      const auto man = mesh_merge::cut_by_plane(geometry::read_mesh(external / "man.off"), {0, 0, 0.36}, {0, 0, 1});
      // Both meshes are z-up and the orbit camera keeps y up: turn them upright, (x, y, z) →
      // (x, z, −y), so the man stands in the first view (a merge does not depend on it).
      return {shared(z_up_to_y_up(devil.above)), shared(z_up_to_y_up(man.below)), "mannequin-devil head", "man body",
              true};
    }
    default:
      throw InvalidArgument("lapis-merge: preset " + std::to_string(preset) + " out of range (0-" +
                            std::to_string(preset_names().size() - 1) + ")");
  }
}

}  // namespace lapis::merge_app
