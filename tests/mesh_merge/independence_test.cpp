#include <doctest/doctest.h>

#include <random>

#include <Eigen/Geometry>

#include "lapis/mesh_merge/metrics.h"
#include "merge_fixtures.h"

using namespace lapis;
using namespace lapis::mesh_merge;

namespace {

// x -> s Q x + t with a uniformly random rotation, log-uniform scale in [0.1, 10] and a
// translation up to 100 units.
TriMesh random_similarity(const TriMesh& m, std::mt19937& rng) {
  std::normal_distribution<double> g(0, 1);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::Quaterniond q(g(rng), g(rng), g(rng), g(rng));
  q.normalize();
  const double s = std::pow(10.0, u(rng));
  const Eigen::RowVector3d t(100 * u(rng), 100 * u(rng), 100 * u(rng));
  TriMesh out = m;
  out.V = (s * (m.V * q.toRotationMatrix().transpose())).rowwise() + t;
  return out;
}

void check_independent(const TriMesh& src, const TriMesh& tgt, const std::vector<LoopPair>& pairs) {
  const MergeResult first = merge(src, tgt, pairs);
  const double tol = 1e-9 * bbox_diagonal(first.mesh.V);  // §3.3.1, the seam included
  std::mt19937 rng(2024);
  double worst = 0;
  for (int k = 0; k < 20; ++k) {
    const MergeResult r = merge(random_similarity(src, rng), tgt, pairs);
    REQUIRE(r.mesh.num_vertices() == first.mesh.num_vertices());
    REQUIRE(r.mesh.F == first.mesh.F);
    worst = std::max(worst, (r.mesh.V - first.mesh.V).rowwise().norm().maxCoeff());
  }
  MESSAGE("largest difference / bbox diagonal: " << worst / bbox_diagonal(first.mesh.V));
  CHECK(worst <= tol);
}

}  // namespace

TEST_CASE("mesh_merge: configuration independence under 20 random similarities (one loop)") {
  const TriMesh src = test::dome(), tgt = test::body();
  check_independent(src, tgt, test::dome_on_body(src, tgt));
}

TEST_CASE("mesh_merge: configuration independence under 20 random similarities (two loops)") {
  const TriMesh src = test::tube(), tgt = test::split_column();
  check_independent(src, tgt, test::tube_in_column(src, tgt));
}

TEST_CASE("mesh_merge: configuration-dependent merging depends on the placement") {
  // The contrast that makes the property above meaningful: §3.3.2 keeps the user's frames.
  const TriMesh src = test::dome(), tgt = test::body();
  MergeOptions o;
  o.mode = MergeMode::Dependent;
  TriMesh placed = src;
  placed.V.col(2).array() += 1.8;
  const MergeResult a = merge(placed, tgt, test::dome_on_body(src, tgt), o);
  TriMesh tilted = placed;
  tilted.V.col(0) += 0.3 * tilted.V.col(2);
  const MergeResult b = merge(tilted, tgt, test::dome_on_body(src, tgt), o);
  CHECK((a.mesh.V - b.mesh.V).rowwise().norm().maxCoeff() > 0.05);
}
