// `lapis merge`: Poisson mesh merging (thesis §3.3) headless — a source part deformed onto a
// target's open boundary, zipped and smoothed, with seam and detail metrics as JSON.
#include <cstdio>
#include <nlohmann/json.hpp>

#include "args.h"
#include "cli_io.h"
#include "command.h"
#include "lapis/core/atomic_file.h"
#include "lapis/geometry/io.h"
#include "lapis/mesh_merge/merge.h"
#include "lapis/mesh_merge/metrics.h"
#include "lapis/mesh_merge/pairs_file.h"
#include "merge_report.h"

namespace lapis::cli {
namespace {

constexpr const char* kUsage =
    "usage: lapis merge --source S --target T --pairs PAIRS.json --out OUT\n"
    "                   [--mode independent|dependent|transition] [--handles H.json] [--smooth N]\n"
    "                   [--roi-width W] [--source-width W] [--target-width W] [--keep source|target]\n"
    "                   [--transition-boundary independent|dependent] [--features F.json] [--report OUT.json]\n"
    "  Deforms the source part so its open boundary loops meet the target's and zips the seams.\n"
    "  independent (default, thesis 3.3.1): the result does not depend on where the source is;\n"
    "  dependent (3.3.2): the source stays where it is, only vertices within --roi-width of its\n"
    "  boundary move (0: the loop diameter) and the --handles vertices stay fixed.\n"
    "  transition (3.3.3, configuration-independent): bands of --source-width and --target-width\n"
    "  (edge-path distance to the loop, target units; default a fifth of the target loop\n"
    "  diameter, shrunk until both bands are annuli)\n"
    "  overlap and blend the two meshes' details; the surface keeps the --keep mesh's band\n"
    "  (default source) and the seam is not smoothed (--smooth is ignored). With\n"
    "  --transition-boundary dependent the bands blend on 3.3.2's boundary condition instead: the\n"
    "  source stays as placed, --roi-width and --handles as in dependent mode.\n"
    "  PAIRS.json: one entry per source boundary loop, each with its key correspondences\n"
    "  (0-based vertex indices, source loop forward = target loop backward):\n"
    "    {\"pairs\": [{\"keys\": [{\"source\": 12, \"target\": 830}, {\"source\": 40, \"target\": 17}]}]}\n"
    "  F.json (independent mode, 3.5): {\"features\": [[40, 41, 42, 57], ...]}, source vertex lists that keep\n"
    "  their shape, each moved by one similarity.\n"
    "  H.json: {\"handles\": [5, 6, 7]}. --smooth: umbrella iterations on the seam (default 3).\n"
    "  Prints the report (timings, seam validity and smoothness, detail preservation) as JSON.\n"
    "       lapis merge --mode optimal --source S --target T --regions R.json --out OUT\n"
    "                   [--placement SCALE,DEGREES,U,V] [--max-iterations N] [--smooth N] [--report OUT.json]\n"
    "  optimal (3.4): finds the merging boundary in the source's band between its rough region and\n"
    "  its feature whose image on the target region changes least (Eq. 3.1), then merges along it.\n"
    "  R.json: {\"rough\": {\"faces\": [...]}, \"feature\": {\"vertices\": [...]}, \"target\": {\"faces\": [...]}}\n"
    "  (faces or vertices each; rough and target default to every face). --placement: the band's\n"
    "  normalized parameterization onto the target region's (scale, rotation in degrees, offset);\n"
    "  default: placed from where the source lies. The report gives the energy per iteration and\n"
    "  the seam and detail metrics of the user's boundary beside the optimal one's.\n";

// The merge options the flags give, but the transition widths (they default to a width
// suggested from the meshes, read later).
mesh_merge::MergeOptions merge_options(const Args& args) {
  mesh_merge::MergeOptions o;
  const std::string mode = args.get("--mode", "independent");
  if (mode == "dependent") {
    o.mode = mesh_merge::MergeMode::Dependent;
  } else if (mode == "transition") {
    o.mode = mesh_merge::MergeMode::Transition;
  } else if (mode != "independent") {
    throw UsageError("--mode must be independent, dependent, transition or optimal, got '" + mode + "'");
  }
  const bool transition = o.mode == mesh_merge::MergeMode::Transition;
  for (const char* flag : {"--source-width", "--target-width", "--keep", "--transition-boundary"})
    if (args.has(flag) && !transition) throw UsageError(std::string(flag) + " needs --mode transition");
  const std::string boundary = args.get("--transition-boundary", "independent");
  if (boundary == "dependent")
    o.transition.configuration_dependent = true;
  else if (boundary != "independent")
    throw UsageError("--transition-boundary must be independent or dependent, got '" + boundary + "'");
  const bool placed = o.mode == mesh_merge::MergeMode::Dependent || o.transition.configuration_dependent;
  const std::string keep = args.get("--keep", "source");
  if (keep == "target")
    o.transition.keep = mesh_merge::TransitionKeep::Target;
  else if (keep != "source")
    throw UsageError("--keep must be source or target, got '" + keep + "'");
  if (args.has("--handles")) {
    if (!placed) throw UsageError("--handles needs --mode dependent or --transition-boundary dependent");
    o.handles = mesh_merge::read_handles_file(args.get("--handles"));
  }
  if (args.has("--features")) {
    if (o.mode != mesh_merge::MergeMode::Independent) throw UsageError("--features needs --mode independent");
    o.features = mesh_merge::read_features_file(args.get("--features"));
  }
  o.smooth_iterations = static_cast<int>(args.get_int("--smooth", o.smooth_iterations, 0, 1000));
  o.roi_width = args.get_double("--roi-width", 0.0, 0.0, 1e300);
  return o;
}

nlohmann::json merge_report(const std::string& out, const geometry::TriMesh& source, const mesh_merge::MergeOptions& o,
                            const mesh_merge::MergeResult& r, const mesh_merge::SeamQuality& q,
                            const mesh_merge::DetailPreservation& d) {
  const bool transition = o.mode == mesh_merge::MergeMode::Transition;
  nlohmann::json j;
  j["mode"] = o.mode == mesh_merge::MergeMode::Dependent ? "dependent" : transition ? "transition" : "independent";
  j["out"] = out;
  j["vertices"] = r.mesh.num_vertices();
  j["faces"] = r.mesh.num_faces();
  j["source_vertices"] = source.num_vertices();
  j["roi_vertices"] = r.roi_vertices;
  j["boundary_refine_levels"] = r.refine_levels;
  j["features"] = o.features.size();
  j["degenerate_vertices"] = r.solver.degenerate_vertices;
  if (transition)
    j["transition"] = {{"source_width", o.transition.source_width},
                       {"target_width", o.transition.target_width},
                       {"weight", o.transition.weight},
                       {"keep", o.transition.keep == mesh_merge::TransitionKeep::Target ? "target" : "source"},
                       {"boundary", o.transition.configuration_dependent ? "dependent" : "independent"},
                       {"band_vertices", r.transition_vertices.size()}};
  j["timings_ms"] = {{"setup", r.timings.setup_ms},
                     {"solve", r.timings.solve_ms},
                     {"zip", r.timings.zip_ms},
                     {"smooth", r.timings.smooth_ms},
                     {"total", r.timings.total_ms}};
  j["seam"] = seam_json(q);
  j["detail"] = detail_json(d);
  return j;
}

int run(const std::vector<std::string>& argv) {
  const Args args(argv);
  if (args.get("--mode", "independent") == "optimal") return run_optimal_merge(args);
  args.allow_only({"--source", "--target", "--pairs", "--out", "--mode", "--handles", "--smooth", "--roi-width",
                   "--source-width", "--target-width", "--keep", "--transition-boundary", "--features", "--report"});
  mesh_merge::MergeOptions o = merge_options(args);
  const bool transition = o.mode == mesh_merge::MergeMode::Transition;
  const std::string out = args.get("--out");
  const geometry::TriMesh source = read_valid_mesh(args.get("--source"));
  const geometry::TriMesh target = read_valid_mesh(args.get("--target"));
  const std::vector<mesh_merge::LoopPair> pairs = mesh_merge::read_pairs_file(args.get("--pairs"));
  if (transition) {
    // Only values the module rejects with a clearer message (<= 0) pass the flag parser as well.
    const bool both_given = args.has("--source-width") && args.has("--target-width");
    const double suggested = both_given ? 0.0 : mesh_merge::suggested_transition_width(source, target, pairs);
    o.transition.source_width = args.get_double("--source-width", suggested, -1e300, 1e300);
    o.transition.target_width = args.get_double("--target-width", suggested, -1e300, 1e300);
  }

  const mesh_merge::MergeResult r = mesh_merge::merge(source, target, pairs, o);
  const mesh_merge::SeamQuality q = mesh_merge::seam_quality(target, r);
  const mesh_merge::DetailPreservation d = mesh_merge::detail_preservation(source, r);

  const nlohmann::json j = merge_report(out, source, o, r, q, d);
  require_finite_numbers(j, "report");  // before the mesh is written: all outputs or none
  core::AtomicFileGroup outputs;        // the mesh and the report: both new or both old
  geometry::write_mesh(out, r.mesh);
  emit_report(j, args);
  outputs.commit();
  return report_invalid_seam(q);
}

}  // namespace

int report_invalid_seam(const mesh_merge::SeamQuality& q) {
  if (q.valid()) return 0;
  if (q.folded_seam_edges > 0)
    std::fprintf(stderr, "lapis merge: error: %d seam edges fold (faces turning by over %.0f degrees)\n",
                 q.folded_seam_edges, geometry::kFoldedDihedralDeg);
  else
    std::fprintf(stderr, "lapis merge: error: the merged seam is not watertight and manifold\n");
  return 1;
}

extern const Command kMergeCommand = {"merge", "merge a mesh part onto another along open boundaries (Poisson merging)",
                                      kUsage, run};

}  // namespace lapis::cli
