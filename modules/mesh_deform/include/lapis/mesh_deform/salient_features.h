// Salient feature extraction (Zhao et al. §3.1): the HKS saliency of every vertex (Step 1),
// best-first region growing from the most salient unclustered vertex (Step 2), and the
// aggregation of connected, highly salient clusters into features (Step 3). The features are
// the vertex sets the salient deformer keeps rigid (§3.2). Users may give or merge features
// (§3.1: "interactively specifying the salient features, or grouping two features into one").
#pragma once

#include <vector>

#include <Eigen/Core>

#include "lapis/geometry/bilateral_denoise.h"
#include "lapis/geometry/connectivity.h"
#include "lapis/mesh_deform/heat_kernel.h"

namespace lapis::mesh_deform {

using Feature = std::vector<int>;  // vertex indices, ascending

// The thresholds the paper names and does not give (§3.1 Step 2–3). The defaults are
// calibrated on the four-spike sphere of Fig. 2 (salient_features_test.cpp): its apexes reach
// s ≈ 0.56, the sphere around them s ≈ −0.1, and the spikes come out as exactly four features.
struct FeatureOptions {
  // §3.1: "the bilateral filtering [41] is first applied to remove the noises". It runs on a
  // copy the spectrum is computed on; the features are vertex sets of the mesh itself.
  // iterations = 0 detects on the mesh as it is.
  geometry::BilateralOptions denoise;
  HeatKernelOptions hks;
  // Step 2's size threshold N_max, as a fraction of #V (at least 4 vertices), so the same
  // options cluster a mesh alike at any resolution.
  double max_cluster_fraction = 0.01;
  // Step 2's saliency threshold s_min: growth stops before the cluster's mean would drop below it.
  double min_cluster_saliency = 0.1;
  // Step 3's "high saliency" s_agg: clusters whose mean reaches it join their connected
  // neighbours' into a feature.
  double aggregate_saliency = 0.25;
  // Skip seeding once the best unclustered saliency is below aggregate_saliency: every later
  // cluster's mean is at most its seed's, so none could be aggregated (same features, faster).
  bool stop_seeding_early = true;

  bool operator==(const FeatureOptions&) const = default;
};

struct FeatureReport {
  int eigenpairs = 0;
  double lambda_2 = 0, lambda_k = 0;  // the spectrum's range the times come from
  double t_min = 0, t_max = 0;
  int clusters = 0;          // grown in Step 2
  int salient_clusters = 0;  // with mean ≥ aggregate_saliency
  int features = 0;
  int dropped_features = 0;  // with fewer than four non-coplanar vertices
  solver::EigenReport eigen;
  double denoise_ms = 0, spectrum_ms = 0, saliency_ms = 0, clustering_ms = 0;
};

struct SalientFeatures {
  Eigen::VectorXd saliency;                // #V
  std::vector<std::vector<int>> clusters;  // Step 2, in seeding order
  std::vector<Feature> features;           // Step 3
  FeatureReport report;
};

// Step 1–3 on mesh. Throws InvalidArgument for an invalid mesh, options out of range
// (eigenpairs ≥ #V among them) or a mesh whose λ₂ is 0 (not connected); the spectrum's errors.
SalientFeatures detect_salient_features(const geometry::TriMesh& mesh, const FeatureOptions& options = {});

// Step 2 alone: clusters grown best-first (the highest-saliency frontier vertex next, ties by
// the lower index) over the mesh's edges.
std::vector<std::vector<int>> grow_clusters(const geometry::Connectivity& conn, const Eigen::VectorXd& saliency,
                                            const FeatureOptions& options);

// Step 3 alone: the union of each edge-connected group of clusters with mean saliency ≥
// aggregate_saliency, without groups of fewer than four non-coplanar vertices (their rotation
// is not determined). P  #V by 3 positions. dropped (optional) counts the groups left out.
std::vector<Feature> aggregate_clusters(const geometry::Connectivity& conn, const geometry::Vertices& P,
                                        const Eigen::VectorXd& saliency, const std::vector<std::vector<int>>& clusters,
                                        double aggregate_saliency, int* dropped = nullptr);

// How user-given features combine with detected ones.
enum class FeatureMerge {
  Replace,  // only the user's
  Union,    // the user's, plus the detected ones minus the vertices the user's take
};

// The combined feature list. Throws InvalidArgument (naming the feature and the vertex) for an
// index outside [0, num_vertices) or a vertex in two user features.
std::vector<Feature> combine_features(const std::vector<Feature>& detected, const std::vector<Feature>& user,
                                      FeatureMerge merge, int num_vertices);

// Features a and b grouped into one (§3.1), the rest in order. Throws InvalidArgument for an
// index out of range or a == b.
std::vector<Feature> merge_two_features(std::vector<Feature> features, int a, int b);

}  // namespace lapis::mesh_deform
