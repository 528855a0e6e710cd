// BVH queries agree with brute force.
#include <doctest/doctest.h>

#include <random>

#include "lapis/core/error.h"
#include "lapis/geometry/bvh.h"
#include "lapis/geometry/io.h"
#include "lapis/geometry/procedural.h"
#include "test_util.h"

using namespace lapis::geometry;

namespace {
std::optional<RayHit> brute_force_hit(const TriMesh& m, const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  std::optional<RayHit> best;
  for (int f = 0; f < m.num_faces(); ++f) {
    const auto hit = intersect_triangle(o, d, m.V.row(m.F(f, 0)), m.V.row(m.F(f, 1)), m.V.row(m.F(f, 2)));
    if (hit && (!best || hit->first < best->t)) best = RayHit{f, hit->first, hit->second, o + hit->first * d};
  }
  return best;
}

TriMesh test_mesh() {
  // A real mesh when available (irregular, with thin triangles), else a bumpy sphere.
  const auto path = test::external_asset("elephant.off");
  if (std::filesystem::exists(path)) return read_mesh(path);
  TriMesh m = make_icosphere(4);
  for (int v = 0; v < m.num_vertices(); ++v) m.V.row(v) *= 1 + 0.2 * std::sin(7 * m.V(v, 0)) * std::cos(5 * m.V(v, 1));
  return m;
}
}  // namespace

TEST_CASE("geometry: BVH ray hits agree with brute force on 10K random rays") {
  const TriMesh m = test_mesh();
  const Bvh bvh(m);
  const Eigen::Vector3d lo = m.V.colwise().minCoeff(), hi = m.V.colwise().maxCoeff();
  const Eigen::Vector3d centre = 0.5 * (lo + hi);
  const double radius = (hi - lo).norm();
  std::mt19937 rng(11);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(0, 1);
  int hits = 0, mismatches = 0;
  for (int i = 0; i < 10000; ++i) {
    // Origins outside and inside the bounding box, aimed at random points near the mesh.
    const Eigen::Vector3d origin =
        centre + (i % 2 ? radius : 0.3 * radius) * Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
    const Eigen::Vector3d target = m.V.row(static_cast<int>(u(rng) * m.num_vertices()) % m.num_vertices()).transpose() +
                                   0.01 * radius * Eigen::Vector3d(g(rng), g(rng), g(rng));
    const Eigen::Vector3d dir = target - origin;
    const auto a = bvh.intersect(origin, dir);
    const auto b = brute_force_hit(m, origin, dir);
    if (a.has_value() != b.has_value() || (a && a->t != b->t)) ++mismatches;
    if (a && b) {
      hits++;
      CHECK(a->t == b->t);
      CHECK((a->point - (origin + a->t * dir)).norm() < 1e-9 * radius);
      const Eigen::Vector3d bary_point = a->barycentric[0] * m.V.row(m.F(a->face, 0)) +
                                         a->barycentric[1] * m.V.row(m.F(a->face, 1)) +
                                         a->barycentric[2] * m.V.row(m.F(a->face, 2));
      CHECK((bary_point - a->point).norm() < 1e-9 * radius);
    }
  }
  CHECK(mismatches == 0);
  CHECK(hits > 5000);  // the rays do test something
  // t_max cuts hits off.
  const Eigen::Vector3d o = centre + Eigen::Vector3d(2 * radius, 0, 0), d(-1, 0, 0);
  const auto far = bvh.intersect(o, d);
  if (far) CHECK_FALSE(bvh.intersect(o, d, 0.5 * far->t).has_value());
}

TEST_CASE("geometry: BVH closest points agree with brute force") {
  const TriMesh m = make_torus(40, 20);
  const Bvh bvh(m);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-2, 2);
  for (int i = 0; i < 500; ++i) {
    const Eigen::Vector3d p(u(rng), u(rng), 0.5 * u(rng));
    const ClosestPoint c = bvh.closest_point(p);
    double best = std::numeric_limits<double>::infinity();
    for (int f = 0; f < m.num_faces(); ++f) {
      const Eigen::Vector3d a = m.V.row(m.F(f, 0)), b = m.V.row(m.F(f, 1)), cc = m.V.row(m.F(f, 2));
      const Eigen::Vector3d w = closest_point_on_triangle(p, a, b, cc);
      best = std::min(best, (w[0] * a + w[1] * b + w[2] * cc - p).norm());
    }
    CHECK(c.distance == doctest::Approx(best).epsilon(1e-12));
    CHECK((c.point - p).norm() == doctest::Approx(c.distance));
    CHECK(c.barycentric.minCoeff() >= 0);
  }
}

TEST_CASE("geometry: BVH inside test on a closed mesh") {
  const Bvh sphere(make_icosphere(3));
  CHECK(sphere.inside(Eigen::Vector3d(0, 0, 0)));
  CHECK(sphere.inside(Eigen::Vector3d(0.5, -0.3, 0.2)));
  CHECK_FALSE(sphere.inside(Eigen::Vector3d(1.2, 0, 0)));
  CHECK_FALSE(sphere.inside(Eigen::Vector3d(0, 0.8, 0.8)));
  const Bvh torus(make_torus(48, 24));
  CHECK(torus.inside(Eigen::Vector3d(1, 0, 0)));
  CHECK_FALSE(torus.inside(Eigen::Vector3d(0, 0, 0)));  // the hole
  CHECK(sphere.depth() < 100);
}

TEST_CASE("geometry: BVH handles degenerate input") {
  const Bvh empty(TriMesh{});
  CHECK_FALSE(empty.intersect(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX()).has_value());
  CHECK_THROWS_WITH_AS(empty.closest_point(Eigen::Vector3d::Zero()),
                       "geometry::Bvh::closest_point(): the mesh has no faces", lapis::InvalidArgument);
  // Many coincident triangles: SAH finds no split, the median fallback keeps the tree shallow.
  TriMesh stack;
  stack.V.resize(3, 3);
  stack.V << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  stack.F = Faces::Zero(5000, 3);
  stack.F.col(1).setConstant(1);
  stack.F.col(2).setConstant(2);
  const Bvh coincident(stack);
  CHECK(coincident.depth() < 20);
  const auto hit = coincident.intersect(Eigen::Vector3d(0.2, 0.2, 1), Eigen::Vector3d(0, 0, -1));
  REQUIRE(hit.has_value());
  CHECK(hit->face == 0);  // ties go to the lowest face index
  CHECK(hit->t == 1.0);
  // Far points: 1e150 away the squared distance (1e300) is finite and the answer exact; at
  // 1e200 every squared distance overflows, and there is no nearest face to name.
  const Bvh sphere(make_icosphere(2));
  const ClosestPoint far = sphere.closest_point(Eigen::Vector3d(0, 1e150, 0));
  REQUIRE(far.face >= 0);
  CHECK(far.distance == doctest::Approx(1e150));
  CHECK(far.point.norm() <= 1.0 + 1e-12);
  CHECK_THROWS_WITH_AS(sphere.closest_point(Eigen::Vector3d(0, 1e200, 0)),
                       doctest::Contains("is so far from the mesh that its squared distance overflows"),
                       lapis::InvalidArgument);
  TriMesh bad = make_icosphere(0);
  bad.V(3, 1) = std::nan("");
  CHECK_THROWS_WITH_AS(Bvh{bad}, doctest::Contains("geometry::Bvh(): vertex 3 = ("), lapis::InvalidArgument);
}

TEST_CASE("geometry: BVH builds over coordinates whose span overflows a double") {
  // A cube at ±1.7e308: every coordinate is finite, but hi - lo and lo + hi are not.
  TriMesh cube = make_box_bar(1, 1, 1, 2, 2, 2);
  const Eigen::RowVector3d centre = 0.5 * (cube.V.colwise().minCoeff() + cube.V.colwise().maxCoeff());
  cube.V = (cube.V.rowwise() - centre) * 1.7e308;
  REQUIRE(cube.V.allFinite());
  REQUIRE(cube.num_faces() == 12);
  const Bvh bvh(cube, BvhOptions{.max_leaf_size = 1});
  CHECK(bvh.num_nodes() == 2 * 12 - 1);  // one triangle per leaf
  CHECK(bvh.depth() <= 12);
}
