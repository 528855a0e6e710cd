// `lapis features`: salient feature detection (Zhao et al. §3.1) headless. Writes the features
// for `lapis deform --method salient --features` and the deform app, a PLY coloured by
// saliency, and a JSON report of each stage (eigenpairs, times, clusters, features).
#include <nlohmann/json.hpp>

#include "args.h"
#include "cli_io.h"
#include "command.h"
#include "lapis/mesh_deform/feature_io.h"
#include "lapis/mesh_deform/salient_features.h"

namespace lapis::cli {
namespace {

using nlohmann::json;
using namespace lapis::mesh_deform;

constexpr const char* kUsage =
    "usage: lapis features --mesh IN --out FEATURES.json [--ply OUT.ply] [--eigenpairs K]\n"
    "                      [--time-scales N] [--max-cluster F] [--min-saliency S] [--aggregate S]\n"
    "                      [--denoise D] [--report OUT.json]\n"
    "  D passes of bilateral denoising (--denoise, 1; 0: none) on a copy of the mesh, then the\n"
    "  heat kernel signature over K eigenpairs (100) and N log-spaced times (16), the saliency\n"
    "  s = mean_t A h_t - 1, clusters grown best-first up to a fraction F of the vertices (0.01)\n"
    "  while their mean stays >= --min-saliency (0.1), and connected clusters with mean >=\n"
    "  --aggregate (0.25) joined into features. FEATURES.json: {\"features\": [[v, ...], ...]}.\n"
    "  --ply writes the mesh coloured by saliency (blue low, red high, features whitened).\n";

FeatureOptions read_options(const Args& args) {
  FeatureOptions o;
  o.denoise.iterations = static_cast<int>(args.get_int("--denoise", o.denoise.iterations, 0, 1000));
  o.hks.eigenpairs = static_cast<int>(args.get_int("--eigenpairs", o.hks.eigenpairs, 2, 100000));
  o.hks.time_scales = static_cast<int>(args.get_int("--time-scales", o.hks.time_scales, 1, 10000));
  o.max_cluster_fraction = args.get_double("--max-cluster", o.max_cluster_fraction, 1e-9, 1);
  o.min_cluster_saliency = args.get_double("--min-saliency", o.min_cluster_saliency, -1e9, 1e9);
  o.aggregate_saliency = args.get_double("--aggregate", o.aggregate_saliency, -1e9, 1e9);
  return o;
}

int run(const std::vector<std::string>& argv) {
  const Args args(argv);
  args.allow_only({"--mesh", "--out", "--ply", "--eigenpairs", "--time-scales", "--max-cluster", "--min-saliency",
                   "--aggregate", "--denoise", "--report"});
  const std::string out_path = args.get("--out");
  const FeatureOptions options = read_options(args);
  const geometry::TriMesh mesh = read_valid_mesh(args.get("--mesh"));
  const SalientFeatures found = detect_salient_features(mesh, options);
  const FeatureReport& r = found.report;
  json sizes = json::array();
  for (const Feature& f : found.features) sizes.push_back(f.size());
  const json report = {{"vertices", mesh.num_vertices()},
                       {"eigenpairs", r.eigenpairs},
                       {"lambda_2", r.lambda_2},
                       {"lambda_k", r.lambda_k},
                       {"t_min", r.t_min},
                       {"t_max", r.t_max},
                       {"lanczos_restarts", r.eigen.restarts},
                       {"eigen_residual", r.eigen.max_residual},
                       {"saliency_min", found.saliency.minCoeff()},
                       {"saliency_max", found.saliency.maxCoeff()},
                       {"clusters", r.clusters},
                       {"salient_clusters", r.salient_clusters},
                       {"features", r.features},
                       {"dropped_features", r.dropped_features},
                       {"feature_sizes", sizes},
                       {"denoise_ms", r.denoise_ms},
                       {"spectrum_ms", r.spectrum_ms},
                       {"saliency_ms", r.saliency_ms},
                       {"clustering_ms", r.clustering_ms}};
  require_finite_numbers(report, "report");
  core::AtomicFileGroup outputs;
  write_features(out_path, found.features);
  if (args.has("--ply")) write_saliency_ply(args.get("--ply"), mesh, found.saliency, found.features);
  emit_report(report, args);
  outputs.commit();
  return 0;
}

}  // namespace

extern const Command kFeaturesCommand = {"features", "detect salient features (heat kernel signature) of a mesh",
                                         kUsage, run};

}  // namespace lapis::cli
