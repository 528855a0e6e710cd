// Naive Laplacian editing (Eq. 2.1) and ARAP (Sorkine & Alexa 2007), and the rotation fit
// under ARAP's local step.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include <Eigen/SVD>

#include "lapis/geometry/polar.h"
#include "lapis/mesh_deform/arap.h"
#include "lapis/mesh_deform/metrics.h"
#include "lapis/mesh_deform/naive_laplacian.h"
#include "rotation_fit.h"
#include "test_meshes.h"

using namespace lapis::mesh_deform;
namespace t = lapis::mesh_deform::test;

namespace {

// A random 3x3 of one of the kinds the local steps meet: generic, a large rotation of a near
// identity (a deformed one-ring), reflected (det < 0), exactly rank 2 (a flat one-ring), nearly
// rank 2, or nearly rank 1 in one direction only (σ3 ≪ σ2 ≪ σ1).
Eigen::Matrix3d random_local_matrix(int kind, std::mt19937& rng) {
  std::normal_distribution<double> g;
  Eigen::Matrix3d A;
  for (int i = 0; i < 9; ++i) A(i) = g(rng);
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(3.1 * g(rng), Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized()).toRotationMatrix();
  switch (kind % 6) {
    case 1:
      return R * (Eigen::Matrix3d::Identity() + 0.1 * A);
    case 2:
      return R * (Eigen::Matrix3d::Identity() + 0.1 * A) * Eigen::Vector3d(1, 1, -0.5).asDiagonal();
    case 3:
      A.col(2) = 0.3 * A.col(0) - 2 * A.col(1);
      return A;
    case 4:
      A.col(2) = 1e-9 * A.col(0) + A.col(1);
      return A;
    case 5:
      return R * Eigen::Vector3d(1, 1e-3, 1e-6).asDiagonal() * Eigen::AngleAxisd(g(rng), Eigen::Vector3d::UnitX());
    default:
      return A;
  }
}

// σ1 / (σ2 + σ3) for signed singular values: the condition of the nearest-rotation problem
// (its answer moves by about κ ε under a relative perturbation ε of A).
double rotation_condition(const Eigen::Matrix3d& A) {
  const Eigen::Vector3d s = Eigen::JacobiSVD<Eigen::Matrix3d>(A).singularValues();
  return s[0] / (s[1] + (A.determinant() < 0 ? -s[2] : s[2]));
}

}  // namespace

TEST_CASE("mesh_deform: nearest rotation equals the SVD polar factor to rounding, from any start") {
  std::mt19937 rng(7);
  std::normal_distribution<double> g;
  int fallbacks = 0;
  for (int k = 0; k < 6000; ++k) {
    const Eigen::Matrix3d A = random_local_matrix(k, rng);
    const Eigen::Matrix3d Rs = lapis::geometry::polar_rotation(A);
    const double kappa = rotation_condition(A);
    // Cold start, a start near the answer (the local steps' case), a random start.
    Eigen::Quaterniond near(Rs * Eigen::AngleAxisd(0.01 * g(rng), Eigen::Vector3d::UnitZ()));
    Eigen::Quaterniond far = Eigen::Quaterniond(Eigen::Vector4d(g(rng), g(rng), g(rng), g(rng))).normalized();
    bool fell_back = false;
    for (const Eigen::Matrix3d& R :
         {detail::nearest_rotation(A, &fell_back), detail::nearest_rotation(A, near, &fell_back),
          detail::nearest_rotation(A, far, &fell_back)}) {
      CHECK((R - Rs).norm() <= 1e-15 * std::max(kappa, 100.0));
      CHECK(std::abs(R.determinant() - 1) < 1e-14);
      CHECK((R.transpose() * R - Eigen::Matrix3d::Identity()).norm() < 1e-14);
      // Optimality: Rᵀ A is symmetric at the maximum of tr(Rᵀ A), to rounding.
      const Eigen::Matrix3d B = R.transpose() * A;
      CHECK((B - B.transpose()).norm() < 1e-14 * A.norm());
    }
    CHECK(near.toRotationMatrix().isApprox(Rs, 1e-15 * std::max(kappa, 1e3)));  // the start is updated
    fallbacks += fell_back;
  }
  CHECK(fallbacks == 0);  // rank ≥ 2 never needs the SVD
}

TEST_CASE("mesh_deform: nearest rotation of rank-1, zero and non-finite matrices") {
  bool fell_back = false;
  CHECK(detail::nearest_rotation(Eigen::Matrix3d::Zero(), &fell_back) == Eigen::Matrix3d::Identity());
  CHECK_FALSE(fell_back);
  const Eigen::Matrix3d nan = Eigen::Matrix3d::Constant(std::nan(""));
  CHECK(detail::nearest_rotation(nan) == Eigen::Matrix3d::Identity());
  // Rank 1: every rotation taking (1,0,0) to (0,1,0) is optimal; the SVD picks one.
  const Eigen::Matrix3d A = Eigen::Vector3d::UnitY() * Eigen::RowVector3d::UnitX();
  const Eigen::Matrix3d R = detail::nearest_rotation(A, &fell_back);
  CHECK(fell_back);
  CHECK((R * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm() < 1e-12);
  CHECK(R.determinant() == doctest::Approx(1.0));
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
    CHECK(d.report().iterations == iters);
    CHECK(d.report().energy <= previous * (1 + 1e-9));
    previous = d.report().energy;
  }
  // All constraints moved by one rigid motion: ARAP reproduces it.
  s.roi = t::all_vertices(m);
  s.region_handles = {t::slab(m, 2, 0.0, 0.1), t::slab(m, 2, 0.9, 1.0)};
  ArapOptions o;
  o.max_iterations = 400;  // ARAP converges linearly and slowly
  ArapDeformer d(m, o);
  d.set_selection(s);
  const Eigen::Matrix4d T =
      t::rotation_about(Eigen::Vector3d(1, 1, 0), 40, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 2, 3));
  const Vertices X = d.deform(HandleTransforms{{T, T}, {}});
  double e = 0;
  for (int i = 0; i < m.num_vertices(); ++i)
    e = std::max(e, (X.row(i).transpose() - apply(T, m.V.row(i).transpose())).norm());
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
  CHECK(d.report().iterations > 1);
  CHECK(d.report().iterations < 500);
  CHECK_THROWS_WITH_AS(d.set_options(ArapOptions{0, 0, true}),
                       "mesh_deform::ArapDeformer::set_options(): max_iterations must be >= 1 and tolerance >= 0",
                       lapis::InvalidArgument);
}
