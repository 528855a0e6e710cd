// `lapis deform`: the mesh_deform module headless. Loads a mesh, an ROI and handles, runs a
// drag (one or more frames of handle transforms) with the chosen method, writes the last
// frame and a JSON report (timings, degenerate vertices, distortion metrics).
#include <chrono>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>

#include "args.h"
#include "cli_io.h"
#include "command.h"
#include "lapis/core/atomic_file.h"
#include "lapis/geometry/io.h"
#include "lapis/mesh_deform/cgal_enclosure.h"
#include "lapis/mesh_deform/edge_laplacian.h"
#include "lapis/mesh_deform/feature_io.h"
#include "lapis/mesh_deform/implicit_laplacian.h"
#include "lapis/mesh_deform/isolines_deformer.h"
#include "lapis/mesh_deform/methods.h"
#include "lapis/mesh_deform/metrics.h"
#include "lapis/mesh_deform/selection_io.h"

namespace lapis::cli {
namespace {

using nlohmann::json;
using namespace lapis::mesh_deform;

// After "--method ": the choices come from the method registry (usage()).
constexpr const char* kUsageRest =
    "\n"
    "                    [--weights cotan|uniform] [--scale-features] [--iterations N]\n"
    "                    [--domain edges|vertices] [--transform rotation|isotropic|anisotropic|full]\n"
    "                    [--frame world|principal] [--tolerance T] [--warm-start] [--soft-handles]\n"
    "                    [--features FEATURES.json] [--no-detect] [--subspace-vertices N] [--eigenpairs K]\n"
    "                    [--subspace lattice|cgal]\n"
    "                    [--isolines N] [--solve reduced|full] [--fit rotation|similarity|paper]\n"
    "                    --out OUT.obj [--report OUT.json]\n"
    "  ROI: vertex indices, as a JSON array or whitespace-separated text; 'all' for every vertex.\n"
    "  HANDLES.json: {\"regions\": [{\"vertices\": [..], \"transforms\": [M, ...]}],\n"
    "                 \"points\": [{\"vertex\": i, \"translations\": [[x, y, z], ...]}]}\n"
    "  with M a 4x4 matrix as 4 rows of 4 numbers applied to rest positions. Each entry of\n"
    "  \"transforms\"/\"translations\" is one frame of a drag (all handles the same frame count,\n"
    "  or 1 = held); the implicit method follows rotations accumulated over the frames.\n"
    "  --scale-features: implicit Eq. 2.11 instead of 2.10. --iterations: ARAP (10) or edge (4)\n"
    "  iterations per frame. --weights: cotan by default, uniform for edge (the paper's).\n"
    "  edge (Wang et al.): --domain edges (the paper) or vertices (its baseline); --transform of\n"
    "  each cell, anisotropic (S R1, the paper's) by default; --frame of the scales, world axes\n"
    "  (the paper's) or principal rest axes; --tolerance stops once no vertex moves more than T\n"
    "  of the bbox diagonal; --warm-start starts each frame from the last one's transforms.\n"
    "  salient (Zhao et al.): --iterations per frame (5); --features adds features (a file of\n"
    "  `lapis features`) to the detected ones, or replaces them with --no-detect; the solid\n"
    "  subspace has about --subspace-vertices vertices (100), a lattice of cubes or CGAL's alpha\n"
    "  wrap tetrahedralised (--subspace cgal); --eigenpairs of the heat kernel (100).\n"
    "  isolines (Au et al.): --isolines per handle (20), --solve reduced (Eq. 10, independent of\n"
    "  #V) or full (Eq. 6), --fit of each isoline's transform, --iterations at most per frame (50)\n"
    "  and --tolerance of the step size (1e-4).\n"
    "  Writes the last frame to OUT; the report holds timings, degenerate vertices, metrics.\n";

const char* usage() {
  static const std::string text =
      "usage: lapis deform --mesh IN --roi ROI --handles HANDLES.json --method " + method_names("|") + kUsageRest;
  return text.c_str();
}

// 'all' or a ROI file (the format is mesh_deform's, shared with the deform app).
std::vector<int> read_roi_arg(const std::string& spec, int n) {
  if (spec != "all") return read_roi(spec);
  std::vector<int> out(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) out[static_cast<size_t>(i)] = i;
  return out;
}

// The edge method's flags over its defaults; a bad name is a usage error naming the choices.
void read_edge_options(const Args& args, LaplacianWeights weights, EdgeLaplacianOptions& o) {
  try {
    o.weights = weights;
    o.iterations = static_cast<int>(args.get_int("--iterations", o.iterations, 1, 1000000));
    o.domain = laplacian_domain_from_name(args.get("--domain", to_string(o.domain)));
    o.transform = cell_transform_from_name(args.get("--transform", to_string(o.transform)));
    o.frame = scale_frame_from_name(args.get("--frame", to_string(o.frame)));
    o.tolerance = args.get_double("--tolerance", o.tolerance, 0, 1);
    o.warm_start = args.has("--warm-start");
    o.soft_handles = args.has("--soft-handles");
  } catch (const InvalidArgument& e) {
    throw UsageError(e.what());
  }
}

// The salient method's flags over its defaults.
void read_salient_options(const Args& args, SalientOptions& o) {
  o.iterations = static_cast<int>(args.get_int("--iterations", o.iterations, 1, 1000000));
  o.subspace_vertices = static_cast<int>(args.get_int("--subspace-vertices", o.subspace_vertices, 8, 100000));
  o.detection.hks.eigenpairs = static_cast<int>(args.get_int("--eigenpairs", o.detection.hks.eigenpairs, 2, 100000));
  o.detect_features = !args.has("--no-detect");
}

json salient_report(const SalientReport& r) {
  return {{"features", r.features},
          {"feature_vertices", r.feature_vertices},
          {"subspace_vertices", r.subspace_vertices},
          {"tets", r.tets},
          {"strays", r.strays},
          {"iterations", r.iterations},
          {"detection_ms", r.detection_ms},
          {"subspace_ms", r.subspace_ms},
          {"embedding_ms", r.embedding_ms},
          {"precompute_ms", r.precompute_ms},
          {"ms_per_iteration", r.ms_per_iteration()},
          {"last_change", r.last_change},
          {"handle_residual", r.handle_residual},
          {"feature_residual", r.feature_residual}};
}

// The isolines method's flags over its defaults.
void read_isolines_options(const Args& args, IsolinesOptions& o) {
  try {
    o.isolines = static_cast<int>(args.get_int("--isolines", o.isolines, 2, 100000));
    o.solve = isoline_solve_from_name(args.get("--solve", to_string(o.solve)));
    o.fit = isoline_fit_from_name(args.get("--fit", to_string(o.fit)));
    o.max_iterations = static_cast<int>(args.get_int("--iterations", o.max_iterations, 1, 1000000));
    o.tolerance = args.get_double("--tolerance", o.tolerance, 0, 1);
  } catch (const InvalidArgument& e) {
    throw UsageError(e.what());
  }
}

json summary(const Summary& s) { return {{"mean", s.mean}, {"max", s.max}, {"p95", s.p95}}; }

int run(const std::vector<std::string>& argv) {
  const Args args(argv, {"--scale-features", "--warm-start", "--soft-handles", "--no-detect"});
  args.allow_only({"--mesh",       "--roi",        "--handles",      "--method",   "--weights",   "--scale-features",
                   "--iterations", "--out",        "--report",       "--domain",   "--transform", "--frame",
                   "--tolerance",  "--warm-start", "--soft-handles", "--features", "--no-detect", "--subspace-vertices",
                   "--eigenpairs", "--subspace",   "--isolines",     "--solve",    "--fit"});
  const std::string method = args.get("--method");
  bool known = false;
  for (const MethodInfo& m : methods()) known = known || method == m.name;
  if (!known) throw UsageError("--method must be one of " + method_names() + ", not '" + method + "'");
  const bool edge = method_from_name(method) == Method::Edge;
  const std::string weights = args.get("--weights", edge ? to_string(EdgeLaplacianOptions{}.weights) : "cotan");
  if (weights != "cotan" && weights != "uniform")
    throw UsageError("--weights must be cotan or uniform, not '" + weights + "'");
  const std::string out_path = args.get("--out");
  const geometry::TriMesh mesh = read_valid_mesh(args.get("--mesh"));
  Drag drag = read_handles(args.get("--handles"));
  drag.selection.roi = read_roi_arg(args.get("--roi"), mesh.num_vertices());
  const LaplacianWeights w = weights == "cotan" ? LaplacianWeights::Cotangent : LaplacianWeights::Uniform;

  MethodSettings settings;
  settings.method = method_from_name(method);
  settings.weights = w;
  settings.scale_features = args.has("--scale-features");
  settings.arap_iterations = static_cast<int>(args.get_int("--iterations", settings.arap_iterations, 1, 1000000));
  if (edge) read_edge_options(args, w, settings.edge);
  if (settings.method == Method::Salient) read_salient_options(args, settings.salient);
  for (const char* flag : {"--features", "--no-detect", "--subspace-vertices", "--eigenpairs", "--subspace"})
    if (args.has(flag) && settings.method != Method::Salient)
      throw UsageError(std::string(flag) + " is an option of --method salient");
  if (settings.method == Method::Isolines) read_isolines_options(args, settings.isolines);
  const std::unique_ptr<Deformer> d = make_deformer(mesh, settings);
  if (auto* s = dynamic_cast<SalientDeformer*>(d.get())) {
    if (args.has("--features")) s->set_features(read_features(args.get("--features")));
    const std::string subspace = args.get("--subspace", "lattice");
    if (subspace != "lattice" && subspace != "cgal")
      throw UsageError("--subspace must be lattice or cgal, not '" + subspace + "'");
    if (subspace == "cgal") {
      EnclosureOptions eo;
      eo.target_vertices = settings.salient.subspace_vertices;
      s->set_subspace(cgal_enclosure(mesh, eo));
    }
  }
  const auto* implicit = dynamic_cast<const ImplicitLaplacianDeformer*>(d.get());
  using clock = std::chrono::steady_clock;
  auto ms = [](clock::time_point t0) { return std::chrono::duration<double, std::milli>(clock::now() - t0).count(); };
  d->set_selection(drag.selection);
  auto t0 = clock::now();
  d->precompute();
  const double setup_ms = ms(t0);
  geometry::TriMesh result = mesh;
  std::vector<double> frame_ms;
  for (const HandleTransforms& t : drag.frames) {
    t0 = clock::now();
    result.V = d->deform(t);
    frame_ms.push_back(ms(t0));
  }

  const Distortion q = distortion(mesh, result.V);
  json r = {{"method", method},
            {"weights", weights},
            {"vertices", mesh.num_vertices()},
            {"frames", frame_ms.size()},
            {"setup_s", setup_ms / 1000},
            {"frame_ms", frame_ms},
            {"distortion",
             {{"edge_length", summary(q.edge_length)},
              {"laplacian_length", summary(q.laplacian_length)},
              {"angle", summary(q.angle)},
              {"arap_energy", q.arap_energy}}}};
  if (implicit) r["degenerate_vertices"] = implicit->report().degenerate_vertices;
  if (const auto* e = dynamic_cast<const EdgeLaplacianDeformer*>(d.get())) {
    const EdgeLaplacianReport& er = e->report();
    r["edge"] = {{"domain", to_string(settings.edge.domain)},
                 {"transform", to_string(settings.edge.transform)},
                 {"frame", to_string(settings.edge.frame)},
                 {"iterations", er.iterations},
                 {"rows", er.rows},
                 {"factor_nnz", er.factor_nnz},
                 {"last_move", er.last_move},
                 {"fit_ms", er.fit_ms},
                 {"solve_ms", er.solve_ms}};
  }
  if (const auto* s = dynamic_cast<const SalientDeformer*>(d.get())) r["salient"] = salient_report(s->report());
  if (const auto* iso = dynamic_cast<const IsolinesDeformer*>(d.get())) {
    const IsolinesReport& ir = iso->report();
    r["isolines"] = {{"solve", to_string(settings.isolines.solve)},
                     {"fit", to_string(settings.isolines.fit)},
                     {"handles", ir.handles},
                     {"sets", ir.sets},
                     {"unknowns", ir.unknowns},
                     {"sampled_triangles", ir.sampled_triangles},
                     {"iterations", ir.iterations},
                     {"iterate_ms", ir.iterate_ms},
                     {"reconstruct_ms", ir.reconstruct_ms},
                     {"field_overshoot", ir.field_overshoot}};
  }
  require_finite_numbers(r, "report");  // before the mesh is written: all outputs or none
  core::AtomicFileGroup outputs;        // the mesh and the report: both new or both old
  geometry::write_mesh(out_path, result);
  emit_report(r, args);
  outputs.commit();
  return 0;
}

}  // namespace

extern const Command kDeformCommand = {
    "deform",
    "drag handles of a mesh: implicit, naive or edge-based Laplacian, ARAP, salient features or handle-aware isolines",
    usage(), run};

}  // namespace lapis::cli
