#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "lapis/geometry/connectivity.h"
#include "lapis/geometry/laplacian.h"
#include "lapis/geometry/normals.h"
#include "lapis/geometry/procedural.h"
#include "lapis/mesh_deform/feature_labels.h"
#include "lapis/mesh_deform/heat_kernel.h"
#include "lapis/mesh_deform/salient_features.h"
#include "salient_meshes.h"

using namespace lapis;
using namespace lapis::mesh_deform;

namespace {

// icosphere(3) (642 vertices) with radii jittered by ±4%: no symmetry, so no multiple eigenvalues.
geometry::TriMesh jittered_sphere(unsigned seed = 4) {
  geometry::TriMesh m = geometry::make_icosphere(3, 1.0);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.96, 1.04);
  for (int i = 0; i < m.num_vertices(); ++i) m.V.row(i) *= u(rng);
  return m;
}

double area(const geometry::TriMesh& m) { return geometry::face_areas(m).sum(); }

// The k in [lo, hi] with the largest gap λ_{k+1} / λ_k: HKS truncated there does not depend on
// the basis the solver picked inside a nearly multiple eigenvalue.
int k_at_gap(const Eigen::VectorXd& values, int lo, int hi) {
  int best = lo;
  for (int k = lo; k <= hi; ++k)
    if (values[k] / values[k - 1] > values[best] / values[best - 1]) best = k;
  return best;
}

solver::Eigenpairs truncated(const solver::Eigenpairs& e, int k) {
  solver::Eigenpairs t;
  t.values = e.values.head(k);
  t.vectors = e.vectors.leftCols(k);
  return t;
}

}  // namespace

TEST_CASE("mesh_deform: HKS from shift-invert Lanczos matches the dense reference") {
  const geometry::TriMesh m = jittered_sphere();
  solver::EigenOptions dense;
  dense.backend = solver::Backend::Eigen;
  const solver::Eigenpairs ref_all = laplacian_spectrum(m, 60, dense);
  const int k = k_at_gap(ref_all.values, 20, 50);
  const solver::Eigenpairs ref = truncated(ref_all, k);
  const solver::Eigenpairs lanczos = laplacian_spectrum(m, k);
  CHECK(std::abs(lanczos.values[0]) < 1e-9);
  for (int i = 1; i < k; ++i) CHECK(std::abs(lanczos.values[i] - ref.values[i]) < 1e-8 * ref.values[i]);
  const solver::SparseMatrix M = geometry::mass_matrix(m);
  const Eigen::MatrixXd G = lanczos.vectors.transpose() * (M * lanczos.vectors);
  CHECK((G - Eigen::MatrixXd::Identity(k, k)).cwiseAbs().maxCoeff() < 1e-10);
  CHECK(lanczos.report.max_residual < 1e-10);
  const Eigen::VectorXd t = heat_kernel_times(ref.values, 16, 1e-4);
  const Eigen::MatrixXd h = scaled_heat_kernel_signature(lanczos, t), h_ref = scaled_heat_kernel_signature(ref, t);
  CHECK(((h - h_ref).cwiseAbs().array() / h_ref.cwiseAbs().array()).maxCoeff() < 1e-8);
  // Σ_x M_xx h_t(x) = 1 at every t, for any k.
  const Eigen::VectorXd mass = M.diagonal();
  for (Eigen::Index c = 0; c < t.size(); ++c) CHECK(std::abs(mass.dot(h.col(c)) - 1) < 1e-10);
}

TEST_CASE("mesh_deform: the sphere's spectrum is 2/r² and its saliency vanishes") {
  const double r = 1.7;
  const geometry::TriMesh m = geometry::make_icosphere(3, r);
  const solver::Eigenpairs e = laplacian_spectrum(m, 9);
  CHECK(std::abs(e.values[0]) < 1e-9);
  for (int i = 1; i <= 3; ++i) CHECK(std::abs(e.values[i] - 2 / (r * r)) < 1e-3 * 2 / (r * r));
  const Eigen::VectorXd s = hks_saliency(e, Eigen::VectorXd::Constant(1, 0.5 * r * r), area(m));
  CHECK(s.cwiseAbs().maxCoeff() < 2e-3);
}

TEST_CASE("mesh_deform: HKS saliency is invariant to a similarity of the mesh") {
  const geometry::TriMesh m = jittered_sphere(11);
  const int k = k_at_gap(laplacian_spectrum(m, 40).values, 15, 35);
  geometry::TriMesh moved = m;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  for (int i = 0; i < m.num_vertices(); ++i)
    moved.V.row(i) = (3.7 * R * m.V.row(i).transpose() + Eigen::Vector3d(5, -2, 1)).transpose();
  auto saliency = [&](const geometry::TriMesh& mesh) {
    const solver::Eigenpairs e = laplacian_spectrum(mesh, k);
    return hks_saliency(e, heat_kernel_times(e.values, 16, 1e-4), area(mesh));
  };
  const Eigen::VectorXd a = saliency(m), b = saliency(moved);
  CHECK((a - b).cwiseAbs().maxCoeff() < 1e-10);
  CHECK(a.cwiseAbs().maxCoeff() > 1e-3);  // not trivially zero
}

TEST_CASE("mesh_deform: the four-spike sphere yields exactly four features holding the apexes") {
  const auto axes = test::tetrahedral_directions();
  const double radius = 0.35;
  const geometry::TriMesh m = test::spiky_sphere(4, axes, radius);
  const FeatureOptions options;
  const SalientFeatures found = detect_salient_features(m, options);
  REQUIRE(found.features.size() == 4);
  CHECK(found.report.features == 4);
  CHECK(found.report.eigenpairs == options.hks.eigenpairs);
  CHECK(found.report.t_min < found.report.t_max);
  std::vector<char> apex_found(4, 0);
  for (const Feature& f : found.features) {
    int spike = -1;
    for (int a = 0; a < 4; ++a)
      if (std::binary_search(f.begin(), f.end(), test::apex_vertex(m, axes[a]))) spike = a;
    REQUIRE(spike >= 0);
    apex_found[spike] = 1;
    for (int v : f) CHECK(std::acos(m.V.row(v).normalized().dot(axes[spike].transpose())) < 1.5 * radius);
  }
  CHECK(std::count(apex_found.begin(), apex_found.end(), 1) == 4);
  // Clusters are connected and no larger than N_max.
  const geometry::Connectivity conn(m);
  const int max_size = std::max(4, static_cast<int>(options.max_cluster_fraction * m.num_vertices()));
  for (const auto& c : found.clusters) {
    CHECK(static_cast<int>(c.size()) <= max_size);
    std::vector<int> reached{c[0]}, seen{c[0]};
    while (!reached.empty()) {
      const int v = reached.back();
      reached.pop_back();
      for (int w : conn.vertex_neighbors(v))
        if (std::binary_search(c.begin(), c.end(), w) && std::find(seen.begin(), seen.end(), w) == seen.end()) {
          seen.push_back(w);
          reached.push_back(w);
        }
    }
    CHECK(seen.size() == c.size());
  }
  // Seeding every vertex gives the same features as stopping once no seed can reach s_agg.
  FeatureOptions all_seeds = options;
  all_seeds.stop_seeding_early = false;
  const SalientFeatures full = detect_salient_features(m, all_seeds);
  CHECK(full.clusters.size() > found.clusters.size());
  CHECK(full.features == found.features);
}

TEST_CASE("mesh_deform: a plain sphere has no salient feature") {
  const SalientFeatures found = detect_salient_features(geometry::make_icosphere(4, 2.0));
  CHECK(found.features.empty());
}

TEST_CASE("mesh_deform: user features replace or join the detected ones") {
  const std::vector<Feature> detected = {{0, 1, 2, 3, 4}, {10, 11, 12, 13}};
  const std::vector<Feature> user = {{4, 3, 20, 21}};
  CHECK(combine_features(detected, user, FeatureMerge::Replace, 30) == std::vector<Feature>{{3, 4, 20, 21}});
  // The detected feature that loses vertices 3 and 4 keeps too few (< 4) and goes.
  CHECK(combine_features(detected, user, FeatureMerge::Union, 30) ==
        std::vector<Feature>{{3, 4, 20, 21}, {10, 11, 12, 13}});
  CHECK(merge_two_features(detected, 1, 0) == std::vector<Feature>{{0, 1, 2, 3, 4, 10, 11, 12, 13}});
  CHECK_THROWS_WITH_AS(combine_features(detected, {{1, 2, 99}}, FeatureMerge::Union, 30),
                       doctest::Contains("feature 0 has vertex 99"), InvalidArgument);
  CHECK_THROWS_WITH_AS(combine_features(detected, {{1, 2}, {2, 5}}, FeatureMerge::Union, 30),
                       doctest::Contains("vertex 2 is in features 0 and 1"), InvalidArgument);
  CHECK_THROWS_AS(merge_two_features(detected, 1, 1), InvalidArgument);
  CHECK_THROWS_WITH_AS(detect_salient_features(geometry::make_icosphere(1), FeatureOptions{}),
                       doctest::Contains("expected 2 <= k < #V = 42"), InvalidArgument);
}

TEST_CASE("mesh_deform: feature labels seed, paint, erase and merge features as an editor does") {
  FeatureLabels labels;
  labels.seed({{0, 1, 2, 3}, {5, 6, 7, 8}}, 12);
  CHECK(labels.count == 2);
  labels.paint({9, 10}, 2);  // a new feature
  labels.paint({3}, FeatureLabels::kNone);
  CHECK(labels.features() == std::vector<Feature>{{0, 1, 2}, {5, 6, 7, 8}, {9, 10}});
  labels.merge(0, 1);
  CHECK(labels.count == 2);
  CHECK(labels.features() == std::vector<Feature>{{0, 1, 2, 5, 6, 7, 8}, {9, 10}});
  CHECK(labels.size_of(1) == 2);
  CHECK_THROWS_WITH_AS(labels.merge(1, 1), doctest::Contains("two different indices"), InvalidArgument);
  CHECK_THROWS_WITH_AS(labels.paint({12}, 0), doctest::Contains("vertex 12 out of range"), InvalidArgument);
}
