// lapis-deform [MESH] [--mesh MESH] [--subdivide N] [--roi ROI] [--handles HANDLES.json]
//              [--method naive|implicit|arap|edge|salient] [--weights cotan|uniform] [--scale-features]
//              [--iterations N] [--full-while-dragging] [--export OUT.obj] [--export-on-exit]
//              [--transfer-target MESH] [--msaa N]
//              [--headless] [--replay EVENTS] [--record EVENTS] [--screenshot OUT.png]
//              [--exit-after-replay] [--benchmark OUT.json] [--ready-file F] [--size WxH]
#include <memory>
#include <string>

#include "args.h"
#include "deform_app.h"
#include "lapis/core/asset_path.h"
#include "lapis/geometry/io.h"
#include "lapis/geometry/procedural.h"
#include "lapis/mesh_deform/methods.h"
#include "lapis/viewer/app_main.h"

namespace {

// After the --method choices, which come from the method registry (usage()).
constexpr const char* kUsageRest =
    "] [--weights cotan|uniform] [--scale-features]\n"
    "                    [--iterations N] [--full-while-dragging] [--export OUT.obj|OUT.ply] [--export-on-exit]\n"
    "                    [--transfer-target MESH] [--distortion-range MAX] [--msaa SAMPLES]\n"
    "                    [--headless] [--replay EVENTS] [--record EVENTS] [--screenshot OUT.png]\n"
    "                    [--exit-after-replay] [--benchmark OUT.json] [--ready-file F] [--size WxH]\n"
    "Opens MESH (OBJ/OFF/PLY/STL; default external/armadillo.off of the assets: $LAPIS_ASSET_DIR,\n"
    "share/lapis of the install or assets/ of the source tree) and the selection files if the ROI\n"
    "file exists (else Ctrl+S creates them). Paint with B (brush) or L\n"
    "(lasso) onto 1 ROI, 2 fixed, 3 handle (N: new handle), Shift erases; X x-ray: brush and lasso\n"
    "select through the surface, hidden vertices too; a click with K takes the clicked vertex's\n"
    "connected part, with G the vertices within a geodesic radius ([ ] size); +/- grow/shrink by a\n"
    "ring; Ctrl+M mirrors the target across a plane through the bounding box's centre. A warning\n"
    "shows when the ROI's border passes within 2 rings of a handle. Drag the gizmo (arrows move,\n"
    "rings rotate, square scales); right-drag orbits, middle-drag pans,\n"
    "wheel zooms, F frames. Ctrl+Z / Ctrl+Shift+Z undo / redo, R reset pose, C colour by distortion,\n"
    "Ctrl+S / Ctrl+O save / open the selection (ROI and handles files of `lapis deform`), Ctrl+E\n"
    "export the deformed mesh with OUT.roi.txt, OUT.handles.json (every solved frame) and\n"
    "OUT.deform.json (the `lapis deform` command that reproduces it), Ctrl+P screenshot, Ctrl+Q quit.\n"
    "--transfer-target opens MESH beside it (deformation transfer, Au et al. 2007): with P (pair) click\n"
    "where each handle, the fixed region first, is on it; every solved frame is carried onto it and\n"
    "Ctrl+E also writes OUT.target.obj with the files `lapis transfer` reproduces it from.\n"
    "--distortion-range opens coloured by distortion on the fixed range [0, MAX] (the panel sets it\n"
    "too), so frames and methods can be compared; without it the range follows each frame's p95.\n";

std::unique_ptr<lapis::viewer::ViewerApp> make_app(std::vector<std::string> rest) {
  using namespace lapis;
  std::string positional;
  if (!rest.empty() && rest[0].rfind("--", 0) != 0) positional = rest[0], rest.erase(rest.begin());
  const cli::Args args(rest, {"--scale-features", "--export-on-exit", "--full-while-dragging"});
  args.allow_only({"--mesh", "--subdivide", "--roi", "--handles", "--method", "--weights", "--scale-features",
                   "--iterations", "--full-while-dragging", "--export", "--export-on-exit", "--transfer-target",
                   "--distortion-range"});
  // --msaa is the viewer's (parse_viewer_flags): multisampling multiplies the fragment work of
  // software rendering, which a 150K-vertex mesh feels; --msaa 0 trades smooth edges for it.
  deform_app::DeformPaths paths;
  // The bundled meshes (external/ of the assets, extracted by scripts/setup) are the file
  // panel's choices and the default mesh; without them, a mesh given opens all the same.
  const bool mesh_given = args.has("--mesh") || !positional.empty();
  try {
    paths.bundled_dir = asset_path("external");
  } catch (const IoError& e) {
    if (!mesh_given) throw IoError(std::string(e.what()) + "; the bundled meshes are extracted by scripts/setup");
  }
  paths.mesh = args.get("--mesh", mesh_given ? positional : (paths.bundled_dir / "armadillo.off").string());
  geometry::TriMesh mesh = geometry::read_mesh(paths.mesh);
  const long levels = args.get_int("--subdivide", 0, 0, 4);
  if (levels > 0) mesh = geometry::loop_subdivide(mesh, static_cast<int>(levels));
  // The mesh's own files unless given (paths_beside: next to it, or in out/ for a bundled one).
  paths = deform_app::paths_beside(paths.mesh, paths, levels > 0 ? ".sub" + std::to_string(levels) : "");
  paths.roi = args.get("--roi", paths.roi.string());
  paths.handles = args.get("--handles", paths.handles.string());
  paths.export_mesh = args.get("--export", paths.export_mesh.string());
  paths.export_on_exit = args.has("--export-on-exit");

  mesh_deform::MethodSettings settings;
  settings.method = mesh_deform::method_from_name(args.get("--method", "implicit"));
  const bool edge = settings.method == mesh_deform::Method::Edge;
  const std::string weights = args.get("--weights", edge ? to_string(settings.edge.weights) : "cotan");
  if (weights != "cotan" && weights != "uniform")
    throw cli::UsageError("--weights must be cotan or uniform, not '" + weights + "'");
  const auto w = weights == "cotan" ? mesh_deform::LaplacianWeights::Cotangent : mesh_deform::LaplacianWeights::Uniform;
  (edge ? settings.edge.weights : settings.weights) = w;
  settings.scale_features = args.has("--scale-features");
  const bool salient = settings.method == mesh_deform::Method::Salient;
  int& iterations = edge                                               ? settings.edge.iterations
                    : salient                                          ? settings.salient.iterations
                    : settings.method == mesh_deform::Method::Isolines ? settings.isolines.max_iterations
                                                                       : settings.arap_iterations;
  iterations = static_cast<int>(args.get_int("--iterations", iterations, 1, 1000));

  auto app =
      std::make_unique<deform_app::DeformApp>(std::move(mesh), paths, settings, !args.has("--full-while-dragging"));
  // The mesh's selection files (given, or its own saved last time) are opened before the first
  // frame (their errors are shown in the window, like every other); a ROI file that does not
  // exist yet is where Ctrl+S will save.
  if (std::filesystem::exists(paths.roi)) app->open_selection_on_start();
  if (args.has("--transfer-target")) app->open_transfer_target_on_start(args.get("--transfer-target"));
  if (args.has("--distortion-range")) app->fix_distortion_range(args.get_double("--distortion-range", 1, 1e-12, 1e12));
  return app;
}

const char* usage() {
  static const std::string text =
      "usage: lapis-deform [MESH] [--mesh MESH] [--subdivide N] [--roi ROI] [--handles HANDLES.json]\n"
      "                    [--method " +
      lapis::mesh_deform::method_names("|") + kUsageRest;
  return text.c_str();
}

}  // namespace

int main(int argc, char** argv) { return lapis::viewer::app_main(argc, argv, "lapis-deform", usage(), make_app); }
