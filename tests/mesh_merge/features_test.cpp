// Fixed features in configuration-independent merging (thesis §3.5): a feature shares one
// deformation gradient, so it moves by one similarity while the rest of the source bends.
#include <doctest/doctest.h>

#include <random>

#include <Eigen/Geometry>

#include "merge_fixtures.h"

namespace lapis::mesh_merge {
namespace {

struct EllipseCase {
  TriMesh source = test::dome(4), target = test::body();
  std::vector<int> cap;  // the dome's top: the feature
  EllipseCase() {
    target.V.col(0) *= 1.7;  // the body's loops become ellipses: the dome must stretch
    for (int v = 0; v < source.num_vertices(); ++v)
      if (source.V(v, 2) > 0.75) cap.push_back(v);
  }
};

TEST_CASE("mesh_merge: a feature with a shared gradient moves by one similarity while the source stretches") {
  const EllipseCase c;
  const auto pairs = test::dome_on_body(c.source, c.target);
  REQUIRE(c.cap.size() > 50);
  const MergeResult plain = merge(c.source, c.target, pairs);
  MergeOptions o;
  o.features = {c.cap};
  const MergeResult kept = merge(c.source, c.target, pairs, o);
  test::require_watertight(c.target, kept);
  const double without = feature_distortion(c.source, plain, c.cap), with = feature_distortion(c.source, kept, c.cap);
  MESSAGE("feature distortion / diameter: " << without << " without, " << with << " with a shared gradient");
  CHECK(without > 0.02);        // the ellipse stretches the cap too
  CHECK(with < 0.1 * without);  // one similarity carries it
}

TEST_CASE("mesh_merge: features keep the merge independent of the source's placement") {
  const EllipseCase c;
  const auto pairs = test::dome_on_body(c.source, c.target);
  MergeOptions o;
  o.features = {c.cap};
  const MergeResult first = merge(c.source, c.target, pairs, o);
  std::mt19937 rng(3);
  std::normal_distribution<double> g;
  for (int k = 0; k < 3; ++k) {
    TriMesh moved = c.source;
    const Eigen::Matrix3d R = Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
    const double s = std::pow(10.0, std::uniform_real_distribution<double>(-1, 1)(rng));
    for (int v = 0; v < moved.num_vertices(); ++v)
      moved.V.row(v) = (s * R * c.source.V.row(v).transpose() + Eigen::Vector3d(5, -3, 2)).transpose();
    const MergeResult r = merge(moved, c.target, pairs, o);
    REQUIRE(r.mesh.F == first.mesh.F);
    CHECK((r.mesh.V - first.mesh.V).cwiseAbs().maxCoeff() < 1e-8);
  }
}

TEST_CASE("mesh_merge: bad features are named errors") {
  const EllipseCase c;
  const auto pairs = test::dome_on_body(c.source, c.target);
  const geometry::Connectivity conn(c.source);
  MergeOptions o;
  o.features = {{conn.boundary_loops()[0][0], c.cap[0], c.cap[1], c.cap[2]}};
  CHECK_THROWS_WITH_AS(merge(c.source, c.target, pairs, o), doctest::Contains("lies on the merging boundary"),
                       InvalidArgument);
  o.features = {c.cap, {c.cap[0], c.cap[1], c.cap[2], c.cap[3]}};
  CHECK_THROWS_WITH_AS(merge(c.source, c.target, pairs, o), doctest::Contains("and in group"), InvalidArgument);
  o.features = {{c.cap[0], c.cap[1]}};
  CHECK_THROWS_WITH_AS(merge(c.source, c.target, pairs, o), doctest::Contains("at least 4"), InvalidArgument);
  o.features = {{0, 1, 2, c.source.num_vertices()}};
  CHECK_THROWS_WITH_AS(merge(c.source, c.target, pairs, o), doctest::Contains("out of range"), InvalidArgument);
  o.features = {c.cap};
  o.mode = MergeMode::Dependent;
  CHECK_THROWS_WITH_AS(merge(c.source, c.target, pairs, o), doctest::Contains("need Independent mode"),
                       InvalidArgument);
}

}  // namespace
}  // namespace lapis::mesh_merge
