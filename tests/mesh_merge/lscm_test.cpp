// Least squares conformal maps and the least-area hole fill, the optimal boundary's
// parameterization (thesis §3.4.2).
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include <Eigen/Geometry>
#include <Eigen/SVD>

#include "cgal_lscm.h"
#include "lapis/core/error.h"
#include "lapis/geometry/connectivity.h"
#include "lapis/geometry/hole_fill.h"
#include "lapis/geometry/polar.h"
#include "lapis/geometry/procedural.h"
#include "lapis/mesh_merge/cut.h"
#include "lapis/mesh_merge/lscm.h"

namespace lapis::mesh_merge {
namespace {

// Singular values of each face's map from 3D (in its own frame) to uv.
std::vector<Eigen::Vector2d> face_stretches(const TriMesh& m, const Eigen::MatrixX2d& uv) {
  std::vector<Eigen::Vector2d> out;
  for (int f = 0; f < m.num_faces(); ++f) {
    const Eigen::Vector3d p0 = m.V.row(m.F(f, 0)), e1 = m.V.row(m.F(f, 1)) - p0.transpose(),
                          e2 = m.V.row(m.F(f, 2)) - p0.transpose();
    const Eigen::Vector3d x = e1.normalized(), y = e1.cross(e2).cross(e1).normalized();
    Eigen::Matrix2d P, U;
    P << e1.dot(x), e2.dot(x), e1.dot(y), e2.dot(y);
    U.col(0) = (uv.row(m.F(f, 1)) - uv.row(m.F(f, 0))).transpose();
    U.col(1) = (uv.row(m.F(f, 2)) - uv.row(m.F(f, 0))).transpose();
    const Eigen::Matrix2d J = U * P.inverse();
    out.push_back(Eigen::JacobiSVD<Eigen::Matrix2d>(J).singularValues());
    if (J.determinant() < 0) out.back() *= -1;  // a flipped face: negative singular values
  }
  return out;
}

TEST_CASE("lscm: a planar patch maps by a similarity of its plane") {
  TriMesh m = geometry::make_irregular_grid(12, 9, 0.2, 4, 1.5, 1.0);
  const std::array<int, 2> pins{0, 12};
  const Eigen::MatrixX2d uv = lscm(m, pins, {Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0)});
  const double s = 1 / (m.V.row(12) - m.V.row(0)).norm();
  for (int v = 0; v < m.num_vertices(); ++v) {
    CHECK(uv(v, 0) == doctest::Approx(s * m.V(v, 0)).epsilon(1e-9));
    CHECK(std::abs(uv(v, 1) - s * m.V(v, 1)) < 1e-9);
  }
}

TEST_CASE("lscm: a cylinder patch unrolls without stretch, and a sphere cap without flips") {
  const TriMesh cylinder = cut_by_plane(geometry::make_cylinder(48, 10, 1.0, 2.0), {0, 0.3, 0}, {0, 1, 0}).above;
  const geometry::Connectivity cc(cylinder);
  REQUIRE(cc.boundary_loops().size() == 1);
  const Eigen::MatrixX2d uv = lscm_pinned_on_loop(cylinder, cc.boundary_loops()[0], true);
  for (const Eigen::Vector2d& sv : face_stretches(cylinder, uv))
    CHECK(sv(0) / sv(1) == doctest::Approx(1).epsilon(1e-6));

  const TriMesh cap = cut_by_plane(geometry::make_icosphere(4), {0, 0, 0.3}, {0, 0, 1}).above;
  const geometry::Connectivity sc(cap);
  const Eigen::MatrixX2d cuv = lscm_pinned_on_loop(cap, sc.boundary_loops()[0], false);
  for (const Eigen::Vector2d& sv : face_stretches(cap, cuv)) CHECK(sv.minCoeff() > 0);
}

TEST_CASE("lscm: a similarity of the mesh leaves the pinned map unchanged") {
  const TriMesh cap = cut_by_plane(geometry::make_icosphere(3), {0, 0, 0.1}, {0, 0, 1}).above;
  const geometry::Connectivity conn(cap);
  const Eigen::MatrixX2d uv = lscm_pinned_on_loop(cap, conn.boundary_loops()[0], false);
  TriMesh moved = cap;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(1.1, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  for (int v = 0; v < cap.num_vertices(); ++v)
    moved.V.row(v) = (7.5 * R * cap.V.row(v).transpose() + Eigen::Vector3d(3, -2, 1)).transpose();
  CHECK((lscm_pinned_on_loop(moved, conn.boundary_loops()[0], false) - uv).cwiseAbs().maxCoeff() < 1e-9);
  // Scaled to area, the uv area equals the surface area.
  const Eigen::MatrixX2d scaled = lscm_pinned_on_loop(moved, conn.boundary_loops()[0], true);
  double area = 0, uv_area = 0;
  for (int f = 0; f < moved.num_faces(); ++f) {
    const int a = moved.F(f, 0), b = moved.F(f, 1), c = moved.F(f, 2);
    area += 0.5 * (moved.V.row(b) - moved.V.row(a)).cross(moved.V.row(c) - moved.V.row(a)).norm();
    const Eigen::Vector2d x = scaled.row(b) - scaled.row(a), y = scaled.row(c) - scaled.row(a);
    uv_area += 0.5 * (x.x() * y.y() - x.y() * y.x());
  }
  CHECK(uv_area == doctest::Approx(area).epsilon(1e-12));
}

TEST_CASE("lscm: unscaled rows agree with CGAL's LSCM_parameterizer_3 on curved patches with the same pins") {
  const TriMesh cap = cut_by_plane(geometry::make_icosphere(3), {0, 0, -0.2}, {0, 0, 1}).above;
  TriMesh bumpy = geometry::make_irregular_grid(16, 12, 0.2, 8, 1.6, 1.2);
  const std::array<const TriMesh*, 2> patches{&cap, &bumpy};
  for (int v = 0; v < bumpy.num_vertices(); ++v) bumpy.V(v, 2) = 0.3 * std::sin(3 * bumpy.V(v, 0)) * bumpy.V(v, 1);
  for (const TriMesh* m : patches) {
    const geometry::Connectivity conn(*m);
    const std::array<int, 2> pins = farthest_pair(*m, conn.boundary_loops()[0]);
    const std::array<Eigen::Vector2d, 2> at{Eigen::Vector2d(0, 0.5), Eigen::Vector2d(1, 0.5)};
    const Eigen::MatrixX2d cgal = peers::cgal_lscm(*m, pins[0], pins[1]);
    CHECK((lscm(*m, pins, at, ConformalWeights::Unscaled) - cgal).cwiseAbs().maxCoeff() < 1e-9);
    // Per-area rows (the paper's energy) weigh the faces differently: a different, nearby map.
    const double apart = (lscm(*m, pins, at) - cgal).cwiseAbs().maxCoeff();
    CHECK(apart > 1e-4);
    CHECK(apart < 2e-2);
  }
}

TEST_CASE("lscm: bad pins are named errors") {
  const TriMesh m = geometry::make_plane_grid(3, 3);
  const std::array<Eigen::Vector2d, 2> at{Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0)};
  CHECK_THROWS_WITH_AS(lscm(m, {0, 0}, at), doctest::Contains("same vertex"), InvalidArgument);
  CHECK_THROWS_WITH_AS(lscm(m, {0, 99}, at), doctest::Contains("out of range"), InvalidArgument);
  CHECK_THROWS_WITH_AS(lscm(m, {0, 3}, {at[0], at[0]}), doctest::Contains("different points"), InvalidArgument);
}

TEST_CASE("minimal_area_fill: n - 2 manifold triangles, exact on a convex polygon, no larger than any fan") {
  // A convex planar polygon: every triangulation has its area.
  geometry::Vertices V(9, 3);
  for (int i = 0; i < 9; ++i) V.row(i) << std::cos(2 * M_PI * i / 9), 0.6 * std::sin(2 * M_PI * i / 9), 0;
  std::vector<int> loop(9);
  for (int i = 0; i < 9; ++i) loop[i] = 8 - i;  // clockwise: the fill faces counter-clockwise (+z)
  const geometry::HoleFill flat = geometry::minimal_area_fill(V, loop);
  CHECK(flat.faces.rows() == 7);
  CHECK(!flat.fan);
  CHECK(flat.area == doctest::Approx(0.5 * 9 * std::sin(2 * M_PI / 9) * 0.6).epsilon(1e-12));
  for (int f = 0; f < flat.faces.rows(); ++f) {
    const Eigen::Vector3d n =
        (V.row(flat.faces(f, 1)) - V.row(flat.faces(f, 0))).cross(V.row(flat.faces(f, 2)) - V.row(flat.faces(f, 0)));
    CHECK(n.z() > 0);
  }
  // A saddle-shaped hole: the fill beats every fan.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  const int k = 14;
  geometry::Vertices W(k, 3);
  for (int i = 0; i < k; ++i)
    W.row(i) << std::cos(2 * M_PI * i / k) + u(rng), std::sin(2 * M_PI * i / k) + u(rng),
        0.8 * std::cos(4 * M_PI * i / k);
  std::vector<int> ring(k);
  for (int i = 0; i < k; ++i) ring[i] = i;
  const geometry::HoleFill fill = geometry::minimal_area_fill(W, ring);
  CHECK(fill.faces.rows() == k - 2);
  const geometry::Connectivity conn(TriMesh{W, fill.faces});
  for (int e = 0; e < conn.num_edges(); ++e) CHECK(conn.edge_face_count(e) <= 2);
  CHECK(conn.boundary_loops().size() == 1);
  for (int apex = 0; apex < k; ++apex) {
    double fan = 0;
    for (int i = 1; i + 1 < k; ++i) {
      const int a = ring[apex], b = ring[(apex + i) % k], c = ring[(apex + i + 1) % k];
      fan += 0.5 * (W.row(b) - W.row(a)).cross(W.row(c) - W.row(a)).norm();
    }
    CHECK(fill.area <= fan * (1 + 1e-12));
  }
  // Above the corner limit: a fan around the centroid.
  const geometry::HoleFill fan = geometry::minimal_area_fill(W, ring, 10);
  CHECK(fan.fan);
  CHECK(fan.faces.rows() == k);
  CHECK(fan.added.rows() == 1);
  CHECK_THROWS_AS(geometry::minimal_area_fill(W, {0, 1}), InvalidArgument);
  CHECK_THROWS_WITH_AS(geometry::minimal_area_fill(W, {0, 1, 1}), doctest::Contains("twice"), InvalidArgument);
}

}  // namespace
}  // namespace lapis::mesh_merge
