#include "lapis/mesh_deform/salient_features.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <queue>
#include <string>

#include "lapis/geometry/laplacian.h"
#include "lapis/geometry/normals.h"

namespace lapis::mesh_deform {
namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void check_options(const FeatureOptions& o, int num_vertices) {
  constexpr const char* fn = "mesh_deform::detect_salient_features()";
  if (o.hks.eigenpairs < 2 || o.hks.eigenpairs >= num_vertices)
    throw InvalidArgument(std::string(fn) + ": hks.eigenpairs = " + std::to_string(o.hks.eigenpairs) +
                          ", expected 2 <= k < #V = " + std::to_string(num_vertices));
  if (o.hks.time_scales < 1 || !(o.hks.truncation > 0 && o.hks.truncation < 1))
    throw InvalidArgument(std::string(fn) + ": expected hks.time_scales >= 1 and hks.truncation in (0, 1)");
  if (!(o.max_cluster_fraction > 0 && o.max_cluster_fraction <= 1) || !std::isfinite(o.min_cluster_saliency) ||
      !std::isfinite(o.aggregate_saliency))
    throw InvalidArgument(std::string(fn) + ": expected max_cluster_fraction in (0, 1] and finite saliency thresholds");
}

// Vertices by decreasing saliency, ties by index: the seeding order of Step 2.
std::vector<int> by_saliency(const Eigen::VectorXd& s) {
  std::vector<int> order(static_cast<size_t>(s.size()));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return s[a] > s[b]; });
  return order;
}

struct Candidate {
  double saliency;
  int vertex;
  bool operator<(const Candidate& o) const {  // max-heap: higher saliency, then lower index
    return saliency != o.saliency ? saliency < o.saliency : vertex > o.vertex;
  }
};

// Whether the points span 3D: a rotation fitted to them is then unique.
bool spans_volume(const geometry::Vertices& P, const Feature& f) {
  if (f.size() < 4) return false;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int v : f) c += P.row(v).transpose();
  c /= static_cast<double>(f.size());
  Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
  for (int v : f) {
    const Eigen::Vector3d d = P.row(v).transpose() - c;
    C += d * d.transpose();
  }
  const Eigen::Vector3d ev = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(C, Eigen::EigenvaluesOnly).eigenvalues();
  return ev[0] > 1e-12 * ev[2];
}

// Union-find root with path halving.
int root(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

std::vector<std::vector<int>> grow_clusters(const geometry::Connectivity& conn, const Eigen::VectorXd& s,
                                            const FeatureOptions& o) {
  const int n = conn.num_vertices();
  const int max_size = std::max(4, static_cast<int>(o.max_cluster_fraction * n));
  std::vector<int> owner(static_cast<size_t>(n), -1), queued(static_cast<size_t>(n), -1);
  std::vector<std::vector<int>> clusters;
  for (int seed : by_saliency(s)) {
    if (owner[seed] >= 0) continue;
    if (o.stop_seeding_early && s[seed] < o.aggregate_saliency) break;
    const int id = static_cast<int>(clusters.size());
    std::vector<int> cluster;
    std::priority_queue<Candidate> frontier;
    double sum = 0;
    auto add = [&](int v) {
      owner[v] = id;
      cluster.push_back(v);
      sum += s[v];
      for (int w : conn.vertex_neighbors(v))
        if (owner[w] < 0 && queued[w] != id) {
          queued[w] = id;
          frontier.push({s[w], w});
        }
    };
    add(seed);
    while (static_cast<int>(cluster.size()) < max_size && !frontier.empty()) {
      const Candidate c = frontier.top();
      frontier.pop();
      if ((sum + c.saliency) / static_cast<double>(cluster.size() + 1) < o.min_cluster_saliency) break;
      add(c.vertex);
    }
    std::sort(cluster.begin(), cluster.end());
    clusters.push_back(std::move(cluster));
  }
  return clusters;
}

std::vector<Feature> aggregate_clusters(const geometry::Connectivity& conn, const geometry::Vertices& P,
                                        const Eigen::VectorXd& s, const std::vector<std::vector<int>>& clusters,
                                        double aggregate_saliency, int* dropped) {
  const int n = conn.num_vertices();
  std::vector<int> owner(static_cast<size_t>(n), -1);
  for (size_t c = 0; c < clusters.size(); ++c) {
    double sum = 0;
    for (int v : clusters[c]) sum += s[v];
    if (!clusters[c].empty() && sum / static_cast<double>(clusters[c].size()) >= aggregate_saliency)
      for (int v : clusters[c]) owner[v] = static_cast<int>(c);
  }
  std::vector<int> parent(clusters.size());
  std::iota(parent.begin(), parent.end(), 0);
  for (const auto& e : conn.edges())
    if (owner[e[0]] >= 0 && owner[e[1]] >= 0 && owner[e[0]] != owner[e[1]])
      parent[root(parent, owner[e[0]])] = root(parent, owner[e[1]]);
  std::vector<int> group_of(clusters.size(), -1);
  std::vector<Feature> groups;
  for (int v = 0; v < n; ++v) {  // vertex order: each feature comes out ascending
    if (owner[v] < 0) continue;
    const int r = root(parent, owner[v]);
    if (group_of[r] < 0) {
      group_of[r] = static_cast<int>(groups.size());
      groups.emplace_back();
    }
    groups[group_of[r]].push_back(v);
  }
  std::vector<Feature> features;
  int left_out = 0;
  for (auto& g : groups) {
    if (spans_volume(P, g))
      features.push_back(std::move(g));
    else
      ++left_out;
  }
  if (dropped) *dropped = left_out;
  return features;
}

SalientFeatures detect_salient_features(const geometry::TriMesh& mesh, const FeatureOptions& o) {
  geometry::require_valid(mesh, {}, "mesh_deform::detect_salient_features()");
  check_options(o, mesh.num_vertices());
  SalientFeatures out;
  FeatureReport& r = out.report;
  auto t0 = std::chrono::steady_clock::now();
  const geometry::TriMesh denoised = geometry::bilateral_denoise(mesh, o.denoise);
  r.denoise_ms = ms_since(t0);
  t0 = std::chrono::steady_clock::now();
  const solver::Eigenpairs spectrum = laplacian_spectrum(denoised, o.hks.eigenpairs, o.hks.eigen);
  r.spectrum_ms = ms_since(t0);
  r.eigen = spectrum.report;
  r.eigenpairs = static_cast<int>(spectrum.values.size());
  r.lambda_2 = spectrum.values[1];
  r.lambda_k = spectrum.values[spectrum.values.size() - 1];

  t0 = std::chrono::steady_clock::now();
  const Eigen::VectorXd times = heat_kernel_times(spectrum.values, o.hks.time_scales, o.hks.truncation);
  r.t_min = times[0];
  r.t_max = times[times.size() - 1];
  out.saliency = hks_saliency(spectrum, times, geometry::face_areas(denoised).sum());
  r.saliency_ms = ms_since(t0);

  t0 = std::chrono::steady_clock::now();
  const geometry::Connectivity conn(mesh);
  out.clusters = grow_clusters(conn, out.saliency, o);
  out.features =
      aggregate_clusters(conn, mesh.V, out.saliency, out.clusters, o.aggregate_saliency, &r.dropped_features);
  r.clustering_ms = ms_since(t0);
  r.clusters = static_cast<int>(out.clusters.size());
  for (const auto& c : out.clusters) {
    double sum = 0;
    for (int v : c) sum += out.saliency[v];
    r.salient_clusters += sum / static_cast<double>(c.size()) >= o.aggregate_saliency;
  }
  r.features = static_cast<int>(out.features.size());
  return out;
}

std::vector<Feature> combine_features(const std::vector<Feature>& detected, const std::vector<Feature>& user,
                                      FeatureMerge merge, int num_vertices) {
  constexpr const char* fn = "mesh_deform::combine_features()";
  std::vector<int> taken(static_cast<size_t>(num_vertices), -1);
  std::vector<Feature> out;
  for (size_t f = 0; f < user.size(); ++f) {
    Feature g = user[f];
    std::sort(g.begin(), g.end());
    g.erase(std::unique(g.begin(), g.end()), g.end());
    for (int v : g) {
      if (v < 0 || v >= num_vertices)
        throw InvalidArgument(std::string(fn) + ": feature " + std::to_string(f) + " has vertex " + std::to_string(v) +
                              ", expected indices in [0, " + std::to_string(num_vertices) + ")");
      if (taken[v] >= 0)
        throw InvalidArgument(std::string(fn) + ": vertex " + std::to_string(v) + " is in features " +
                              std::to_string(taken[v]) + " and " + std::to_string(f));
      taken[v] = static_cast<int>(f);
    }
    if (!g.empty()) out.push_back(std::move(g));
  }
  if (merge == FeatureMerge::Replace) return out;
  for (const Feature& d : detected) {
    Feature rest;
    for (int v : d)
      if (v >= 0 && v < num_vertices && taken[v] < 0) rest.push_back(v);
    if (rest.size() >= 4) out.push_back(std::move(rest));
  }
  return out;
}

std::vector<Feature> merge_two_features(std::vector<Feature> features, int a, int b) {
  const int n = static_cast<int>(features.size());
  if (a < 0 || b < 0 || a >= n || b >= n || a == b)
    throw InvalidArgument("mesh_deform::merge_two_features(): features " + std::to_string(a) + " and " +
                          std::to_string(b) + ", expected two different indices in [0, " + std::to_string(n) + ")");
  Feature& into = features[std::min(a, b)];
  const Feature& from = features[std::max(a, b)];
  into.insert(into.end(), from.begin(), from.end());
  std::sort(into.begin(), into.end());
  into.erase(std::unique(into.begin(), into.end()), into.end());
  features.erase(features.begin() + std::max(a, b));
  return features;
}

}  // namespace lapis::mesh_deform
