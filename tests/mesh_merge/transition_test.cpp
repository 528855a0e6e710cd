// Overlapped transition regions (thesis §3.3.3): the bands, their unit-square
// parameterizations, and merges whose band blends the two meshes' Laplacian coordinates.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>

#include <Eigen/Geometry>

#include "lapis/geometry/dijkstra.h"
#include "lapis/geometry/laplacian.h"
#include "lapis/mesh_merge/metrics.h"
#include "lapis/mesh_merge/transition.h"
#include "merge_fixtures.h"

using namespace lapis;
using namespace lapis::mesh_merge;

namespace {

// The dome with bumps of amplitude 0.04 and wavelength ~0.6 (a few edges of a level-4 sphere):
// details the smooth body lacks.
TriMesh bumpy_dome() {
  TriMesh s = geometry::make_icosphere(4, 1.0);
  for (int v = 0; v < s.num_vertices(); ++v) {
    const Eigen::RowVector3d p = s.V.row(v);
    s.V.row(v) *= 1 + 0.04 * std::sin(10 * p.x()) * std::sin(10 * p.y()) * std::sin(10 * p.z() + 1);
  }
  test::jitter(s, 0.002, 3);
  return cut_by_plane(s, {0, 0, 0.2}, {0, 0, 1}).above;
}

MergeOptions transition_options(TransitionKeep keep = TransitionKeep::Source) {
  MergeOptions o;
  o.mode = MergeMode::Transition;
  o.transition.source_width = 0.35;
  o.transition.target_width = 0.35;
  o.transition.keep = keep;
  return o;
}

// |mean curvature normal| per vertex: the cotangent Laplacian coordinate over the Voronoi area.
Eigen::VectorXd curvature_magnitude(const TriMesh& m) {
  const Eigen::MatrixX3d d = geometry::laplacian_coordinates(m);
  const Eigen::VectorXd a = geometry::vertex_areas(m);
  return (d.rowwise().norm().array() / a.array()).matrix();
}

void require_valid(const TriMesh& target, const MergeResult& r) {
  test::require_watertight(target, r);
  // The body's bottom loop is all that stays open, in one piece.
  CHECK(geometry::Connectivity(r.mesh).boundary_loops().size() == 1);
  CHECK(geometry::connected_components(r.mesh).count == 1);
  CHECK(geometry::genus(r.mesh) == 0);
}

}  // namespace

TEST_CASE("mesh_merge: a transition band is an annulus parameterized one-to-one over the unit square") {
  const TriMesh tgt = test::body();
  const geometry::Connectivity conn(tgt);
  const auto pairs = test::dome_on_body(test::dome(), tgt);
  std::vector<int> loop;
  for (const auto& l : conn.boundary_loops())
    if (std::find(l.begin(), l.end(), pairs[0].keys[0].target) != l.end()) loop = l;
  std::rotate(loop.begin(), std::find(loop.begin(), loop.end(), pairs[0].keys[0].target), loop.end());
  for (bool reversed : {false, true}) {
    std::vector<int> l = loop;
    if (reversed) std::reverse(l.begin() + 1, l.end());
    const TransitionBand b = transition_band(tgt, conn, l, arc_length_params(tgt.V, l), 0.35, reversed, "target");
    // Every band vertex is closer than the width to the loop (rings 0.1 apart: 4 rings), the rim is the next ring.
    CHECK(b.vertices.size() == 4 * l.size());
    CHECK(b.rim.size() == l.size());
    CHECK(b.cut.front() == l[0]);
    CHECK(b.cut.back() == b.rim[0]);
    // Inside the square, loop at v = 0, rim at v = 1, and no triangle flipped: one-to-one.
    CHECK(b.uv.minCoeff() >= -1e-12);
    CHECK(b.uv.maxCoeff() <= 1 + 1e-12);
    for (int v : l) CHECK(b.at(v).y() == 0.0);
    for (int v : b.rim) CHECK(b.at(v).y() == 1.0);
    int positive = 0, negative = 0;
    double area = 0;
    for (Eigen::Index f = 0; f < b.param_faces.rows(); ++f) {
      const Eigen::Vector2d p = b.uv.row(b.param_faces(f, 0)), q = b.uv.row(b.param_faces(f, 1)),
                            r = b.uv.row(b.param_faces(f, 2));
      const double a = 0.5 * ((q - p).x() * (r - p).y() - (q - p).y() * (r - p).x());
      positive += a > 1e-15, negative += a < -1e-15;
      area += a;
    }
    CHECK((positive == 0 || negative == 0));
    CHECK(std::abs(area) == doctest::Approx(1.0).epsilon(1e-9));  // the triangles tile the square
  }
}

// On both boundary conditions: §3.3.1's (the source scaled to the target's loop) and §3.3.2's
// (the source as placed, slightly too small on top of the body).
TEST_CASE("mesh_merge: transition overlap points map a band onto the other at (u, 1 - v)") {
  for (const bool dependent : {false, true}) {
    CAPTURE(dependent);
    TriMesh src = test::dome(4);
    if (dependent) {
      src.V *= 0.9;
      src.V.col(2).array() += 1.85;
    }
    const TriMesh tgt = test::body();
    MergeOptions o = transition_options();
    o.transition.configuration_dependent = dependent;
    MergeResult r = merge(src, tgt, test::dome_on_body(src, tgt), o);
    // Through the public pieces: the source band's loop lands on the target band's rim.
    const geometry::Connectivity sc(r.source_rest), tc(tgt);
    const auto corr = correspond_boundaries(r.source_rest, sc, tgt, tc, test::dome_on_body(src, tgt));
    const std::vector<double> tu = arc_length_params(tgt.V, corr[0].target_loop);
    const TransitionBand t = transition_band(tgt, tc, corr[0].target_loop, tu, 0.35, true, "target");
    const TransitionBand s =
        transition_band(r.source_rest, sc, corr[0].source_loop, arc_length_params(r.source_rest.V, corr[0].source_loop),
                        0.35, false, "source");
    const std::vector<BandPoint> on_t = overlap_points(s, t);
    REQUIRE(on_t.size() == s.vertices.size());
    std::vector<char> rim(static_cast<size_t>(tgt.num_vertices()), 0);
    for (int v : t.rim) rim[v] = 1;
    for (size_t k = 0; k < s.vertices.size(); ++k) {
      double sum = 0;
      for (int j = 0; j < 3; ++j) {
        sum += on_t[k].weights[j];
        CHECK(on_t[k].weights[j] >= 0);
      }
      CHECK(sum == doctest::Approx(1.0));
      // Mapping back through the weights reproduces (u, 1 − v).
      // (A vertex on t's cut has two parameter points; take the one on p's side of the square.)
      const Eigen::Vector2d p = s.at(s.vertices[k]);
      Eigen::Vector2d q = Eigen::Vector2d::Zero();
      for (int j = 0; j < 3; ++j) {
        Eigen::Vector2d c = t.at(on_t[k].vertices[j]);
        for (size_t i = 0; i < t.param_vertex.size(); ++i)
          if (t.param_vertex[i] == on_t[k].vertices[j] && std::abs(t.uv(i, 0) - p.x()) < std::abs(c.x() - p.x()))
            c = t.uv.row(i).transpose();
        q += on_t[k].weights[j] * c;
      }
      CHECK((q - Eigen::Vector2d(p.x(), 1 - p.y())).norm() < 1e-9);
      if (std::find(s.loop.begin(), s.loop.end(), s.vertices[k]) != s.loop.end())
        for (int j = 0; j < 3; ++j)
          if (on_t[k].weights[j] > 1e-9) CHECK(rim[on_t[k].vertices[j]]);
    }
  }
}

TEST_CASE("mesh_merge: transition merging is watertight, manifold and leaves the target beyond its band unmoved") {
  const TriMesh src = bumpy_dome(), tgt = test::body();
  const auto pairs = test::dome_on_body(src, tgt);
  const double width = 0.35;
  // The body's rings are 0.1 apart and its top loop is at z = 2: the band is z > 2 − width.
  // Configuration-dependent boundary conditions (§3.3.2) take the source as placed: on the body,
  // as the dependent test below places it.
  TriMesh placed = src;
  placed.V *= 0.9;
  placed.V.col(2).array() += 1.85;
  for (auto [keep, dependent] : {std::pair{TransitionKeep::Source, false}, std::pair{TransitionKeep::Target, false},
                                 std::pair{TransitionKeep::Source, true}}) {
    CAPTURE(static_cast<int>(keep));
    CAPTURE(dependent);
    MergeOptions o = transition_options(keep);
    o.transition.configuration_dependent = dependent;
    const MergeResult r =
        dependent ? merge(placed, tgt, test::dome_on_body(placed, tgt), o) : merge(src, tgt, pairs, o);
    require_valid(tgt, r);
    int kept = 0, moved = 0;
    for (int v = 0; v < tgt.num_vertices(); ++v) {
      const int m = r.target_map[v];
      if (m < 0 || tgt.V(v, 2) > 2 - width - 0.05) continue;
      ++kept;
      moved += r.mesh.V.row(m) != tgt.V.row(v);
    }
    CHECK(kept > tgt.num_vertices() / 2);
    CHECK(moved == 0);
    const SeamQuality q = seam_quality(tgt, r);
    CHECK(q.max_target_displacement == 0.0);
    CHECK(!r.transition_vertices.empty());
    CHECK(r.roi_vertices > src.num_vertices());  // the target's band is in the ROI too
    CHECK(r.transition_vertices.size() == r.transition_share.size());
  }
}

TEST_CASE("mesh_merge: the transition band's Laplacian coordinates blend between the two meshes'") {
  // A bumpy dome onto a smooth body: across the band, the mean curvature magnitude goes from the
  // body's (small) at the target side to the dome's (bumpy) at the source side, monotonically.
  const TriMesh src = bumpy_dome(), tgt = test::body();
  const auto pairs = test::dome_on_body(src, tgt);
  const Eigen::VectorXd ks = curvature_magnitude(src), kt = curvature_magnitude(tgt);
  const geometry::Connectivity sc(src), tc(tgt);
  double src_mean = 0, tgt_mean = 0;
  int ns = 0, nt = 0;
  for (int v = 0; v < src.num_vertices(); ++v)
    if (!sc.is_boundary_vertex(v)) src_mean += ks(v), ++ns;
  for (int v = 0; v < tgt.num_vertices(); ++v)
    if (!tc.is_boundary_vertex(v)) tgt_mean += kt(v), ++nt;
  src_mean /= ns, tgt_mean /= nt;
  REQUIRE(src_mean > 2 * tgt_mean);  // the premise: the dome is much bumpier than the body

  // Configuration-dependent boundary conditions (§3.3.2) take the source as placed: on the body,
  // as the dependent test below places it.
  TriMesh placed = src;
  placed.V *= 0.9;
  placed.V.col(2).array() += 1.85;
  for (auto [keep, dependent] : {std::pair{TransitionKeep::Source, false}, std::pair{TransitionKeep::Target, false},
                                 std::pair{TransitionKeep::Source, true}}) {
    CAPTURE(static_cast<int>(keep));
    CAPTURE(dependent);
    MergeOptions o = transition_options(keep);
    o.transition.configuration_dependent = dependent;
    const MergeResult r =
        dependent ? merge(placed, tgt, test::dome_on_body(placed, tgt), o) : merge(src, tgt, pairs, o);
    // Scale back to the inputs' units: curvature scales with 1 / length (the source was brought
    // to the target's loop perimeter, so the merged mesh is in the target's units already).
    const Eigen::VectorXd km = curvature_magnitude(r.mesh);
    const geometry::Connectivity mc(r.mesh);
    constexpr int kBins = 3;
    std::array<double, kBins> sum{}, count{};
    for (size_t k = 0; k < r.transition_vertices.size(); ++k) {
      const int v = r.transition_vertices[k];
      if (mc.is_boundary_vertex(v)) continue;
      const double tau = r.transition_share[k];
      if (tau <= 0.02 || tau >= 0.98) continue;  // the band's ends touch the zipped strip
      const int bin = std::min(kBins - 1, static_cast<int>(tau * kBins));
      sum[bin] += km(v), count[bin] += 1;
    }
    std::array<double, kBins> mean{};
    for (int b = 0; b < kBins; ++b) {
      REQUIRE(count[b] > 10);
      mean[b] = sum[b] / count[b];
      MESSAGE("target share bin " << b << ": mean curvature " << mean[b] << " (target " << tgt_mean << ", source "
                                  << src_mean << ")");
      CHECK(mean[b] > 0.8 * tgt_mean);
      CHECK(mean[b] < 1.2 * src_mean);
    }
    // More target share, less bump: strictly decreasing with margin.
    for (int b = 1; b < kBins; ++b) CHECK(mean[b] < 0.95 * mean[b - 1]);
  }
}

TEST_CASE("mesh_merge: transition merging is configuration-independent") {
  const TriMesh src = test::dome(3), tgt = test::body();
  const auto pairs = test::dome_on_body(src, tgt);
  const MergeOptions o = transition_options();
  const MergeResult first = merge(src, tgt, pairs, o);
  const double tol = 1e-6 * bbox_diagonal(first.mesh.V);
  std::mt19937 rng(77);
  std::normal_distribution<double> g(0, 1);
  std::uniform_real_distribution<double> u(-1, 1);
  double worst = 0;
  for (int k = 0; k < 5; ++k) {
    Eigen::Quaterniond q(g(rng), g(rng), g(rng), g(rng));
    q.normalize();
    TriMesh moved = src;
    moved.V = (std::pow(10.0, u(rng)) * (src.V * q.toRotationMatrix().transpose())).rowwise() +
              Eigen::RowVector3d(100 * u(rng), 100 * u(rng), 100 * u(rng));
    const MergeResult r = merge(moved, tgt, pairs, o);
    REQUIRE(r.mesh.F == first.mesh.F);
    worst = std::max(worst, (r.mesh.V - first.mesh.V).rowwise().norm().maxCoeff());
  }
  MESSAGE("largest difference / bbox diagonal: " << worst / bbox_diagonal(first.mesh.V));
  CHECK(worst <= tol);
}

TEST_CASE("mesh_merge: transition regions on configuration-dependent boundary conditions keep the placement") {
  // The user's placement: the bumpy dome on top of the body, slightly too small; its apex held.
  TriMesh src = bumpy_dome();
  src.V *= 0.9;
  src.V.col(2).array() += 1.85;
  const TriMesh tgt = test::body();
  const auto pairs = test::dome_on_body(src, tgt);
  std::vector<int> handles;
  for (int v = 0; v < src.num_vertices(); ++v)
    if (src.V(v, 2) > 2.6) handles.push_back(v);
  REQUIRE(!handles.empty());
  MergeOptions o = transition_options();
  o.transition.configuration_dependent = true;
  o.handles = handles;
  o.roi_width = 0.45;
  const MergeResult r = merge(src, tgt, pairs, o);
  require_valid(tgt, r);
  CHECK(!r.transition_vertices.empty());
  for (double tau : r.transition_share) CHECK((tau >= 0 && tau <= 1));
  // The source stays as placed: handles exactly, and every vertex beyond the ROI and the band.
  const geometry::Connectivity sc(src);
  std::vector<int> loop = sc.boundary_loops()[0];
  const geometry::ShortestPaths d = geometry::dijkstra(src, loop);
  int far = 0;
  for (int h : handles) CHECK(r.mesh.V.row(r.source_map[h]) == src.V.row(h));
  for (int v = 0; v < src.num_vertices(); ++v)
    if (d.distance[v] > 0.5 && r.source_map[v] >= 0) {
      ++far;
      CHECK(r.mesh.V.row(r.source_map[v]) == src.V.row(v));
    }
  CHECK(far > src.num_vertices() / 3);
  // The frames are kept, so the result follows the placement: turning the source turns its top,
  // where §3.3.1's boundary condition would give the same merge.
  TriMesh turned = src;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const Eigen::RowVector3d pivot(0, 0, 2);
  for (int v = 0; v < src.num_vertices(); ++v) turned.V.row(v) = (src.V.row(v) - pivot) * R.transpose() + pivot;
  const MergeResult t = merge(turned, tgt, pairs, o);
  require_valid(tgt, t);
  for (int h : handles) CHECK(t.mesh.V.row(t.source_map[h]) == turned.V.row(h));
  MergeOptions independent = transition_options();
  const MergeResult a = merge(src, tgt, pairs, independent), b = merge(turned, tgt, pairs, independent);
  REQUIRE(a.mesh.F == b.mesh.F);
  CHECK((a.mesh.V - b.mesh.V).cwiseAbs().maxCoeff() < 1e-6);
  // A handle inside the source band cannot stay fixed while the band blends.
  int inside = -1;
  for (int v = 0; v < src.num_vertices() && inside < 0; ++v)
    if (d.distance[v] > 0.05 && d.distance[v] < 0.2) inside = v;
  REQUIRE(inside >= 0);
  o.handles = {inside};
  CHECK_THROWS_WITH_AS(merge(src, tgt, pairs, o), doctest::Contains("lies in the source transition band"),
                       InvalidArgument);
}

TEST_CASE("mesh_merge: transition merging rejects bad widths with clear errors") {
  const TriMesh src = test::dome(), tgt = test::body();
  const auto pairs = test::dome_on_body(src, tgt);
  auto with = [&](double sw, double tw) {
    MergeOptions o = transition_options();
    o.transition.source_width = sw;
    o.transition.target_width = tw;
    return o;
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (auto [sw, tw] : {std::pair{0.0, 0.3}, std::pair{0.3, -1.0}, std::pair{nan, 0.3}, std::pair{0.3, nan}})
    CHECK_THROWS_WITH_AS(
        merge(src, tgt, pairs, with(sw, tw)),
        doctest::Contains("mesh_merge::merge(): transition source_width and target_width must be finite and > 0"),
        InvalidArgument);
  // The widths as given, not rounded to six decimals ("-0.000000" before).
  CHECK_THROWS_WITH_AS(merge(src, tgt, pairs, with(-2e-9, 0.3)), doctest::Contains("got -2e-09 and 0.3"),
                       InvalidArgument);
  MergeOptions bad_weight = transition_options();
  bad_weight.transition.weight = 0;
  CHECK_THROWS_WITH_AS(merge(src, tgt, pairs, bad_weight), doctest::Contains("weight w_T must be finite and > 0"),
                       InvalidArgument);
  // A source band wider than the dome swallows it.
  CHECK_THROWS_WITH_AS(merge(src, tgt, pairs, with(5.0, 0.3)),
                       doctest::Contains("mesh_merge::transition_band(): the source transition band of width 5 covers "
                                         "the whole mesh (no face is that far from the merging loop)"),
                       InvalidArgument);
  // A target band reaching the body's other (bottom) loop leaves no target beyond it.
  CHECK_THROWS_WITH_AS(merge(src, tgt, pairs, with(0.3, 1.95)),
                       doctest::Contains("the target transition band of width 1.95 covers the whole mesh"),
                       InvalidArgument);
  // A hole in the body's side just below the top: the band around the top loop reaches it.
  std::vector<int> hole;
  for (int f = 0; f < tgt.num_faces(); ++f) {
    Eigen::RowVector3d c = Eigen::RowVector3d::Zero();
    for (int k = 0; k < 3; ++k) c += tgt.V.row(tgt.F(f, k)) / 3;
    if ((c - Eigen::RowVector3d(1, 0, 1.7)).norm() < 0.15) hole.push_back(f);
  }
  const TriMesh holed = geometry::remove_faces(tgt, hole);
  REQUIRE(geometry::Connectivity(holed).boundary_loops().size() == 3);
  CHECK_THROWS_WITH_AS(merge(src, holed, test::dome_on_body(src, holed), with(0.3, 0.35)),
                       doctest::Contains("the target transition band of width 0.35 is not an annulus"),
                       InvalidArgument);
  // Two pairs whose source bands meet in the middle of the tube (scaled to length 2).
  const TriMesh tube = test::tube(), column = test::split_column();
  CHECK_THROWS_WITH_AS(merge(tube, column, test::tube_in_column(tube, column), with(1.1, 0.2)),
                       doctest::Contains("mesh_merge::merge(): the transition bands of pairs 0 and 1 overlap"),
                       InvalidArgument);
}

TEST_CASE("mesh_merge: a transition band narrower than an edge is just the loop") {
  const TriMesh src = test::dome(), tgt = test::body();
  for (TransitionKeep keep : {TransitionKeep::Source, TransitionKeep::Target}) {
    MergeOptions o = transition_options(keep);
    o.transition.source_width = o.transition.target_width = 0.01;
    const MergeResult r = merge(src, tgt, test::dome_on_body(src, tgt), o);
    CHECK(seam_quality(tgt, r).valid());
    CHECK(geometry::validate(r.mesh).ok());
  }
}

TEST_CASE("mesh_merge: transition merging of two loop pairs at once") {
  const TriMesh tube = test::tube(), column = test::split_column();
  MergeOptions o = transition_options();
  o.transition.source_width = o.transition.target_width = 0.25;
  const MergeResult r = merge(tube, column, test::tube_in_column(tube, column), o);
  const SeamQuality q = seam_quality(column, r);
  CHECK(q.valid());
  CHECK(geometry::validate(r.mesh).ok());
  CHECK(geometry::Connectivity(r.mesh).boundary_loops().size() == 2);  // the column's outer ends
  CHECK(geometry::connected_components(r.mesh).count == 1);
}
