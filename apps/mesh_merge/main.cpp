// lapis-merge [--source MESH --target MESH | --preset N] [--export PREFIX] [viewer flags]
// Opens two meshes for Poisson merging (thesis §3.3); without meshes, the bundled dome and neck.
#include <memory>

#include "args.h"
#include "bundled_meshes.h"
#include "lapis/core/asset_path.h"
#include "lapis/geometry/io.h"
#include "lapis/geometry/mesh_edit.h"
#include "lapis/mesh_merge/regions_file.h"
#include "lapis/viewer/app_main.h"
#include "merge_app.h"

namespace {

constexpr const char* kUsage =
    "usage: lapis-merge [--source MESH --target MESH | --preset N] [--export PREFIX] [--headless]\n"
    "                   [--replay EVENTS] [--record EVENTS] [--screenshot OUT.png] [--exit-after-replay]\n"
    "                   [--benchmark OUT.json] [--ready-file F] [--size WxH] [--regions R.json]\n"
    "Presets: 0 dome onto neck (default), 1 placed dome onto neck, 2 devil's head onto the man.\n"
    "Left-click with the current tool: 1 pair loops, 2 key correspondences, 3 fixed handles; left-drag:\n"
    "4 moves the source with the gizmo, 5 paints a region (Shift erases) that C cuts off; X x-ray: the brush\n"
    "paints through the surface, so the cut goes all round an arm. Right-drag orbits,\n"
    "middle-drag pans, wheel zooms, F frames. A new pair gets a key suggested as the source is placed;\n"
    "K suggests them again (after moving the source); a result turned over (face-down) or folded is\n"
    "flagged in red. D switches independent / dependent mode, T transition regions on / off, M merges, Tab\n"
    "shows result or inputs, Ctrl+Z / Ctrl+Shift+Z undo / redo, Ctrl+E exports PREFIX.obj (merged),\n"
    "PREFIX_source.obj, PREFIX_target.obj, PREFIX_pairs.json and the equivalent `lapis merge` command\n"
    "(default PREFIX out/merge); with --export the files are also written on exit. Ctrl+P screenshot,\n"
    "Ctrl+Q quit. --regions opens in the optimal-boundary mode (thesis 3.4) with the regions of a\n"
    "`lapis merge --mode optimal` regions file; tool 5 then paints the region chosen in the panel.\n";

std::unique_ptr<lapis::viewer::ViewerApp> make_app(const std::vector<std::string>& rest) {
  using namespace lapis;
  const cli::Args args(rest);
  args.allow_only({"--source", "--target", "--preset", "--export", "--regions"});
  merge_app::AppPaths paths;
  paths.asset_dir = asset_path("merge").parent_path();
  if (args.has("--export")) paths.export_prefix = args.get("--export"), paths.export_on_exit = true;
  if (args.has("--source") != args.has("--target")) throw cli::UsageError("--source and --target go together");
  merge_app::MeshPair meshes;
  if (args.has("--source")) {
    meshes.source = std::make_shared<const geometry::TriMesh>(geometry::read_mesh(args.get("--source")));
    meshes.target = std::make_shared<const geometry::TriMesh>(geometry::read_mesh(args.get("--target")));
    meshes.source_name = std::filesystem::path(args.get("--source")).filename().string();
    meshes.target_name = std::filesystem::path(args.get("--target")).filename().string();
  } else {
    const long preset = args.get_int("--preset", 0, 0, static_cast<long>(merge_app::preset_names().size()) - 1);
    meshes = merge_app::load_preset_meshes(static_cast<int>(preset), paths.asset_dir);
  }
  mesh_merge::MergeSetup setup;
  setup.source = meshes.source;
  setup.target = meshes.target;
  if (meshes.place_source) setup.placement = mesh_merge::suggest_placement(*meshes.source, *meshes.target);
  if (args.has("--regions")) {
    const mesh_merge::BoundaryRegions r =
        mesh_merge::read_regions_file(args.get("--regions"), *meshes.source, *meshes.target);
    setup.options.mode = mesh_merge::MergeMode::OptimalBoundary;
    setup.optimal.rough = geometry::vertices_of_faces(*meshes.source, r.roi_faces);
    setup.optimal.feature = geometry::vertices_of_faces(*meshes.source, r.feature_faces);
    setup.optimal.target = geometry::vertices_of_faces(*meshes.target, r.target_faces);
  }
  return std::make_unique<merge_app::MergeApp>(std::move(setup), meshes.source_name, meshes.target_name, paths);
}

}  // namespace

int main(int argc, char** argv) { return lapis::viewer::app_main(argc, argv, "lapis-merge", kUsage, make_app); }
