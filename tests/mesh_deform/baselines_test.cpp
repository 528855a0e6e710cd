// Naive Laplacian editing (Eq. 2.1) and ARAP (Sorkine & Alexa 2007), and the rotation fit
// under ARAP's local step.
#include <doctest/doctest.h>

#include <random>

#include "lapis/mesh_deform/arap.h"
#include "lapis/mesh_deform/metrics.h"
#include "lapis/mesh_deform/naive_laplacian.h"
#include "lapis/geometry/polar.h"
#include "rotation_fit.h"
#include "test_meshes.h"

using namespace lapis::mesh_deform;
namespace t = lapis::mesh_deform::test;

TEST_CASE("mesh_deform: nearest rotation matches the SVD polar factor, also for rank-2 and reflected input") {
  std::mt19937 rng(7);
  std::normal_distribution<double> g;
  int fallbacks = 0;
  for (int k = 0; k < 2000; ++k) {
    Eigen::Matrix3d A;
    for (int i = 0; i < 9; ++i) A(i) = g(rng);
    if (k % 3 == 0) A = Eigen::AngleAxisd(3.1, Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized()) * (Eigen::Matrix3d::Identity() + 0.1 * A);
    if (k % 3 == 1) A.col(2) = 1e-9 * A.col(0) + A.col(1);  // rank 2, like a flat one-ring
    bool fell_back = false;
    const Eigen::Matrix3d R = detail::nearest_rotation(A, &fell_back);
    fallbacks += fell_back;
    const Eigen::Matrix3d Rs = lapis::geometry::polar_rotation(A);
    CHECK((R - Rs).norm() < 1e-7);
    CHECK(R.determinant() == doctest::Approx(1.0));
  }
  CHECK(fallbacks == 0);
}

TEST_CASE("mesh_deform: naive hard handles reach their targets, soft ones only approach them") {
  const TriMesh m = t::box_bar(3, 1.0, 3.0);
  const Selection s = t::bottom_fixed_top_handle(m, 2, 0.1, 0.1);
  HandleTransforms h = HandleTransforms::identity(s);
  h.regions[0].topRightCorner<3, 1>() = Eigen::Vector3d(0.8, 0, 0);
  NaiveLaplacianDeformer hard(m);
  NaiveOptions so;
  so.soft_handles = true;
  NaiveLaplacianDeformer soft(m, so);
  hard.set_selection(s);
  soft.set_selection(s);
  const Vertices Xh = hard.deform(h), Xs = soft.deform(h);
  double eh = 0, es = 0, moved = 0;
  for (int v : s.region_handles[0]) {
    eh = std::max(eh, (Xh.row(v) - m.V.row(v) - Eigen::RowVector3d(0.8, 0, 0)).norm());
    es = std::max(es, (Xs.row(v) - m.V.row(v) - Eigen::RowVector3d(0.8, 0, 0)).norm());
    moved = std::max(moved, (Xs.row(v) - m.V.row(v)).norm());
  }
  CHECK(eh < 1e-9);
  CHECK(es > 1e-3);
  CHECK(moved > 0.4);
  // Fixed region untouched by both.
  for (int v = 0; v < m.num_vertices(); ++v)
    if (m.V(v, 2) < 0.05 * 3.0) CHECK((Xs.row(v) - m.V.row(v)).norm() == 0.0);
}

TEST_CASE("mesh_deform: ARAP energy decreases monotonically and a rigid drag stays rigid") {
  const TriMesh m = t::box_bar(3, 1.0, 4.0);
  Selection s = t::bottom_fixed_top_handle(m, 2, 0.1, 0.1);
  const HandleTransforms h{{t::rotation_about(Eigen::Vector3d::UnitY(), 60, Eigen::Vector3d(1.5, 0.5, 0.4))}, {}};
  double previous = 1e300;
  for (int iters : {1, 2, 4, 8, 16, 32}) {
    ArapOptions o;
    o.max_iterations = iters;
    ArapDeformer d(m, o);
    d.set_selection(s);
    d.deform(h);
    CHECK(d.stats().iterations == iters);
    CHECK(d.stats().energy <= previous * (1 + 1e-9));
    previous = d.stats().energy;
  }
  // All constraints moved by one rigid motion: ARAP reproduces it.
  s.roi = t::all_vertices(m);
  s.region_handles = {t::slab(m, 2, 0.0, 0.1), t::slab(m, 2, 0.9, 1.0)};
  ArapOptions o;
  o.max_iterations = 400;  // ARAP converges linearly and slowly
  ArapDeformer d(m, o);
  d.set_selection(s);
  const Eigen::Matrix4d T = t::rotation_about(Eigen::Vector3d(1, 1, 0), 40, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 2, 3));
  const Vertices X = d.deform(HandleTransforms{{T, T}, {}});
  double e = 0;
  for (int i = 0; i < m.num_vertices(); ++i) e = std::max(e, (X.row(i).transpose() - apply(T, m.V.row(i).transpose())).norm());
  CHECK(e < 1e-6);
}

TEST_CASE("mesh_deform: ARAP stops early at its tolerance") {
  const TriMesh m = t::box_bar(3, 1.0, 4.0);
  const Selection s = t::bottom_fixed_top_handle(m, 2, 0.1, 0.1);
  ArapOptions o;
  o.max_iterations = 500;
  o.tolerance = 1e-3;
  ArapDeformer d(m, o);
  d.set_selection(s);
  d.deform(HandleTransforms{{t::rotation_about(Eigen::Vector3d::UnitX(), 30, Eigen::Vector3d(0.5, 0.5, 3.6))}, {}});
  CHECK(d.stats().iterations > 1);
  CHECK(d.stats().iterations < 500);
  CHECK_THROWS_WITH_AS(d.set_options(ArapOptions{0, 0, true}),
                       "mesh_deform::ArapDeformer::set_options(): max_iterations must be >= 1 and tolerance >= 0",
                       lapis::InvalidArgument);
}
