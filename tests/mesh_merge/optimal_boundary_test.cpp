// The optimal merging boundary (thesis §3.4): the loop it returns, its optimality for fixed T
// against an independent search, its invariances, and the merge along it.
#include <doctest/doctest.h>

#include <omp.h>
#include <cmath>
#include <limits>
#include <random>
#include <set>

#include "lapis/geometry/connectivity.h"
#include "lapis/geometry/dijkstra.h"
#include "lapis/geometry/hole_fill.h"
#include "lapis/geometry/mesh_edit.h"
#include "lapis/mesh_merge/lscm.h"
#include "lapis/mesh_merge/metrics.h"
#include "optimal_fixtures.h"

namespace lapis::mesh_merge {
namespace {

using test::bump_regions;
using test::bump_with_ripples;
using test::flat_target;

struct BumpCase {
  geometry::TriMesh source = bump_with_ripples(), target = flat_target();
  BoundaryOptimizer optimizer{source, target, bump_regions(source)};
  OptimalBoundary boundary = optimizer.optimize(optimizer.suggested_placement());
};

const BumpCase& bump_case() {
  static const BumpCase c;
  return c;
}

std::set<int> band_vertices(const BoundaryOptimizer& opt) {
  std::set<int> out;
  for (int f : opt.band_faces())
    for (int j = 0; j < 3; ++j) out.insert(opt.source().F(f, j));
  return out;
}

TEST_CASE("optimal boundary: a simple loop of band vertices that encloses the feature and nothing outside Ω0") {
  const BumpCase& c = bump_case();
  const std::vector<int>& loop = c.boundary.loop;
  REQUIRE(loop.size() >= 3);
  CHECK(std::set<int>(loop.begin(), loop.end()).size() == loop.size());
  const std::set<int> band = band_vertices(c.optimizer);
  const geometry::Connectivity conn(c.source);
  for (size_t i = 0; i < loop.size(); ++i) {
    CHECK(band.count(loop[i]) == 1);
    CHECK(conn.find_edge(loop[i], loop[(i + 1) % loop.size()]) >= 0);
  }
  const MergeResult r = c.optimizer.merge(c.boundary);
  std::set<int> in_rough;
  for (int f : bump_regions(c.source).roi_faces)
    for (int j = 0; j < 3; ++j) in_rough.insert(c.source.F(f, j));
  for (int f : c.optimizer.feature_faces())
    for (int j = 0; j < 3; ++j) CHECK(r.source_map[c.source.F(f, j)] >= 0);
  for (int v = 0; v < c.source.num_vertices(); ++v)
    if (!in_rough.count(v)) CHECK(r.source_map[v] == -1);
}

TEST_CASE("optimal boundary: never worse than the user's boundary, and each boundary step lowers E for its T") {
  const OptimalBoundary& b = bump_case().boundary;
  CHECK(b.energy <= b.user_energy);
  CHECK(b.energy < 0.05 * b.user_energy);  // the ripples beyond r1 cost ∂Ω0 dearly
  REQUIRE(b.history.size() >= 2);
  for (size_t k = 0; k + 1 < b.history.size(); ++k)
    CHECK(b.history[k].step_energy <= b.history[k].energy * (1 + 1e-12));
  CHECK(std::isnan(b.history.back().step_energy));
  CHECK(b.energy == doctest::Approx(b.history[b.best_iteration].energy).epsilon(1e-15));
}

// Edge steps from ∂Ωf through the band, breadth first.
std::vector<int> steps_from_feature(const BoundaryOptimizer& opt) {
  const geometry::Connectivity conn(geometry::with_faces(opt.source(), opt.band_faces()));
  std::vector<int> steps(static_cast<size_t>(opt.source().num_vertices()), std::numeric_limits<int>::max());
  std::vector<int> queue;
  for (int v : opt.inner_loop()) steps[v] = 0, queue.push_back(v);
  for (size_t i = 0; i < queue.size(); ++i)
    for (int u : conn.vertex_neighbors(queue[i]))
      if (steps[u] > steps[queue[i]] + 1) steps[u] = steps[queue[i]] + 1, queue.push_back(u);
  return steps;
}

// Bellman–Ford over the band's universal cover (vertex, winding sheet): a closed walk from w back
// to w that winds once around the hole, found without the cut-open graph the optimizer uses,
// through vertices at least `clearance` edge steps from ∂Ωf.
double cheapest_winding_loop(const BoundaryOptimizer& opt, const Vertices& image, const geometry::Similarity3& T,
                             int clearance) {
  const geometry::TriMesh band = geometry::with_faces(opt.source(), opt.band_faces());
  const geometry::Connectivity conn(band);
  const std::vector<int> steps = steps_from_feature(opt);
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  // inside the filled hole in uv
  for (int v : opt.inner_loop()) centre += opt.source_uv().row(v).transpose();
  centre /= static_cast<double>(opt.inner_loop().size());
  auto angle = [&](int v) {
    const Eigen::Vector2d d = opt.source_uv().row(v).transpose() - centre;
    return std::atan2(d.y(), d.x());
  };
  constexpr int kSheets = 5, kMid = 2;
  const double inf = std::numeric_limits<double>::infinity();
  double best = inf;
  for (int w : opt.cut()) {  // every loop around the hole meets the cut
    std::vector<double> dist(static_cast<size_t>(band.num_vertices()) * kSheets, inf);
    dist[static_cast<size_t>(w) * kSheets + kMid] = 0;
    for (bool changed = true; changed;) {
      changed = false;
      for (int e = 0; e < conn.num_edges(); ++e)
        for (int dir = 0; dir < 2; ++dir) {
          const int a = conn.edges()[e][dir], b = conn.edges()[e][1 - dir];
          if (steps[a] < clearance || steps[b] < clearance) continue;
          double turn = angle(b) - angle(a);
          const int wrap = turn > M_PI ? -1 : turn < -M_PI ? 1 : 0;  // crossing the branch cut of atan2
          const double cost = boundary_energy(opt.source().V, image, {a, b}, T) / 2;  // the loop counts a-b twice
          for (int s = 0; s < kSheets; ++s) {
            const int t = s + wrap;
            if (t < 0 || t >= kSheets || dist[a * kSheets + s] == inf) continue;
            if (dist[a * kSheets + s] + cost < dist[b * kSheets + t] * (1 - 1e-15))
              dist[b * kSheets + t] = dist[a * kSheets + s] + cost, changed = true;
          }
        }
    }
    best = std::min({best, dist[w * kSheets + kMid + 1], dist[w * kSheets + kMid - 1]});
  }
  return best;
}

// With feature_clearance 0 (§3.4 as written, ∂Ωf allowed) and with clearances of 1 (the default)
// and 2 edges, which the reference honours on its own.
TEST_CASE("optimal boundary: at fixed T the boundary step is the exact cheapest loop around the feature") {
  const geometry::TriMesh src = bump_with_ripples(14), tgt = flat_target(20);
  for (int clearance : {0, 1, 2}) {
    CAPTURE(clearance);
    OptimalBoundaryOptions o;
    o.feature_clearance = clearance;
    const BoundaryOptimizer opt(src, tgt, bump_regions(src), o);
    const OptimalBoundary b = opt.optimize(opt.suggested_placement());
    REQUIRE(band_vertices(opt).size() < 400);
    const std::vector<int> steps = steps_from_feature(opt);
    for (const BoundaryIteration& it : b.history) {
      double cost = 0;
      const std::vector<int> loop = opt.cheapest_loop(b.image, it.transform, &cost);
      CHECK(cost == doctest::Approx(cheapest_winding_loop(opt, b.image, it.transform, clearance)).epsilon(1e-9));
      CHECK(cost <= boundary_energy(src.V, b.image, opt.outer_loop(), it.transform) * (1 + 1e-12));
      if (clearance == 0) CHECK(cost <= boundary_energy(src.V, b.image, opt.inner_loop(), it.transform) * (1 + 1e-12));
      for (int v : loop) CHECK(steps[v] >= clearance);
    }
  }
}

geometry::Similarity3 random_similarity(std::mt19937& rng) {
  std::normal_distribution<double> n;
  geometry::Similarity3 G;
  G.R = Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
  G.s = std::pow(10.0, std::uniform_real_distribution<double>(-1, 1)(rng));
  G.t = Eigen::Vector3d(n(rng), n(rng), n(rng));
  return G;
}

geometry::TriMesh transformed(const geometry::TriMesh& m, const geometry::Similarity3& G) {
  geometry::TriMesh out = m;
  for (int v = 0; v < m.num_vertices(); ++v) out.V.row(v) = G(m.V.row(v).transpose()).transpose();
  return out;
}

TEST_CASE("optimal boundary: a similarity of the source keeps the loop and scales the energy") {
  const BumpCase& c = bump_case();
  const Placement2D placement = c.optimizer.suggested_placement();
  std::mt19937 rng(5);
  for (int trial = 0; trial < 10; ++trial) {
    const geometry::Similarity3 G = random_similarity(rng);
    const BoundaryOptimizer opt(transformed(c.source, G), c.target, bump_regions(c.source));
    const OptimalBoundary b = opt.optimize(placement);
    CHECK(b.loop == c.boundary.loop);
    CHECK(b.energy / G.s == doctest::Approx(c.boundary.energy).epsilon(1e-9));
    CHECK((b.transform.linear() * G.linear() - c.boundary.transform.linear()).norm() < 1e-9);
  }
}

TEST_CASE("optimal boundary: onto a similar copy of the filled band the energy vanishes and T is the similarity") {
  const geometry::TriMesh src = bump_with_ripples(20);
  const BoundaryRegions regions = bump_regions(src);
  const BoundaryOptimizer probe(src, flat_target(), regions);
  // D: the band with ∂Ωf filled as the optimizer fills it.
  const std::vector<int> hole(probe.inner_loop().rbegin(), probe.inner_loop().rend());
  const geometry::HoleFill fill = geometry::minimal_area_fill(src.V, hole);
  geometry::TriMesh disk = geometry::with_faces(src, probe.band_faces());
  disk.F.conservativeResize(disk.F.rows() + fill.faces.rows(), 3);
  disk.F.bottomRows(fill.faces.rows()) = fill.faces;
  std::mt19937 rng(9);
  for (int trial = 0; trial < 3; ++trial) {
    geometry::Similarity3 G = random_similarity(rng);
    if (trial == 0) G = geometry::Similarity3();
    const BoundaryOptimizer opt(src, transformed(disk, G), regions);
    // The pins are the same vertices on both, so the target uv is the source uv scaled.
    const std::array<int, 2> pins = farthest_pair(src, opt.outer_loop());
    const Eigen::Vector2d a = opt.target_uv().row(pins[0]), d = opt.target_uv().row(pins[1]) - a.transpose();
    Placement2D p;
    p.scale = d.norm(), p.angle = std::atan2(d.y(), d.x()), p.offset = a;
    const OptimalBoundary b = opt.optimize(p);
    double edge_sq = 0;
    for (size_t i = 0; i < b.loop.size(); ++i)
      edge_sq += (src.V.row(b.loop[i]) - src.V.row(b.loop[(i + 1) % b.loop.size()])).squaredNorm();
    CHECK(b.energy <= 1e-12 * G.s * edge_sq);
    CHECK((b.transform.linear() - G.linear()).norm() < 1e-9 * G.s);
  }
}

TEST_CASE("optimal boundary: on a bump with ripples beyond r1 the boundary stays in the flat ring") {
  const BumpCase& c = bump_case();
  double outer = 0, user_inner = 9;
  for (int v : c.boundary.loop) outer = std::max(outer, test::radius_of(c.source, v));
  for (int v : c.boundary.user_loop) user_inner = std::min(user_inner, test::radius_of(c.source, v));
  CHECK(outer < test::kFlatRadius);
  CHECK(user_inner > test::kFlatRadius);
}

TEST_CASE("optimal boundary: the merge along it keeps details better than along the user's boundary") {
  const BumpCase& c = bump_case();
  MergeOptions free;  // Ωf bends with the rest, as §3.4.1 merges: the boundary's own merit
  free.hold_feature = false;
  const MergeResult optimal = c.optimizer.merge(c.boundary, free), user = c.optimizer.merge(c.boundary, free, true);
  const SeamQuality q = seam_quality(c.target, optimal);
  CHECK(q.valid());
  CHECK(q.folded_seam_edges == 0);
  CHECK(seam_quality(c.target, user).valid());
  // detail_preservation() normalizes over each merge's own source part; compare the part both
  // keep, the feature, by its distance from a similar copy of itself.
  const DetailPreservation dp = detail_preservation(c.source, optimal), du = detail_preservation(c.source, user);
  CHECK(dp.max_distance <= du.max_distance);
  const std::vector<int> feature = geometry::vertices_of_faces(c.source, c.optimizer.feature_faces());
  const double along_optimal = feature_distortion(c.source, optimal, feature),
               along_user = feature_distortion(c.source, user, feature);
  MESSAGE("feature distortion, Ωf free: " << along_optimal << " along the optimal boundary, " << along_user
                                          << " along ∂Ω0");
  CHECK(along_optimal < 0.05 * along_user);
  // The flat target stays flat away from the bump: the seam ring lies on it.
  for (int v : optimal.seam_vertices) CHECK(std::abs(optimal.mesh.V(v, 2)) < 0.01);
}

// §3.5 on Ωf (MergeOptions::hold_feature, the default): the feature moves by one similarity
// along either boundary, while the rest of the part still bends to meet the target.
TEST_CASE("optimal boundary: the merge holds Ωf's shape by a shared gradient along either boundary") {
  const BumpCase& c = bump_case();
  MergeOptions free;
  free.hold_feature = false;
  const MergeResult held = c.optimizer.merge(c.boundary), held_user = c.optimizer.merge(c.boundary, {}, true),
                    free_user = c.optimizer.merge(c.boundary, free, true);
  CHECK(seam_quality(c.target, held).valid());
  CHECK(seam_quality(c.target, held_user).valid());
  const std::vector<int> feature = geometry::vertices_of_faces(c.source, c.optimizer.feature_faces());
  const double d_held = feature_distortion(c.source, held, feature),
               d_held_user = feature_distortion(c.source, held_user, feature),
               d_free_user = feature_distortion(c.source, free_user, feature);
  MESSAGE("feature distortion: " << d_held << " along the optimal boundary, " << d_held_user << " along ∂Ω0 held, "
                                 << d_free_user << " free");
  CHECK(d_held_user < 0.1 * d_free_user);
  CHECK(d_held <= d_held_user);
  // Not a rigid copy of the whole part: outside Ωf the band still bends onto the plate.
  CHECK(detail_preservation(c.source, held_user).max_distance > 10 * d_held_user);
  for (int v : held.seam_vertices) CHECK(std::abs(held.mesh.V(v, 2)) < 0.01);
}

TEST_CASE("optimal boundary: stopping rules and the energy history") {
  const BumpCase& c = bump_case();
  CHECK(c.boundary.stopped_by == "fixed point");
  const size_t n = c.boundary.history.size();
  REQUIRE(n >= 2);
  CHECK(c.boundary.history[n - 1].energy == c.boundary.history[n - 2].energy);
  auto run_with = [&](const OptimalBoundaryOptions& o) {
    return BoundaryOptimizer(c.source, c.target, bump_regions(c.source), o).optimize(c.optimizer.suggested_placement());
  };
  OptimalBoundaryOptions capped, loose;
  capped.max_iterations = 1;
  loose.relative_tolerance = 1e6;
  const OptimalBoundary b = run_with(capped), l = run_with(loose);
  CHECK(b.stopped_by == "iteration cap");
  CHECK(b.history.size() == 2);
  CHECK(l.stopped_by == "energy change");
  CHECK(l.history.size() == 2);
}

TEST_CASE("optimal boundary: the cut is a shortest path across the band, off both borders inside") {
  const BumpCase& c = bump_case();
  const std::vector<int>& cut = c.optimizer.cut();
  REQUIRE(cut.size() >= 2);
  const std::set<int> outer(c.optimizer.outer_loop().begin(), c.optimizer.outer_loop().end());
  const std::set<int> inner(c.optimizer.inner_loop().begin(), c.optimizer.inner_loop().end());
  CHECK(outer.count(cut.front()) == 1);
  CHECK(inner.count(cut.back()) == 1);
  for (size_t i = 1; i + 1 < cut.size(); ++i) CHECK((outer.count(cut[i]) + inner.count(cut[i])) == 0);
  double length = 0;
  for (size_t i = 0; i + 1 < cut.size(); ++i) length += (c.source.V.row(cut[i + 1]) - c.source.V.row(cut[i])).norm();
  const geometry::ShortestPaths d =
      geometry::dijkstra(c.source, c.optimizer.outer_loop(), geometry::edge_length_cost(c.source));
  double across = std::numeric_limits<double>::infinity();
  for (int v : inner) across = std::min(across, d.distance[v]);
  CHECK(length == doctest::Approx(across).epsilon(1e-12));
}

TEST_CASE("optimal boundary: bad regions and placements are named errors") {
  const geometry::TriMesh src = bump_with_ripples(20), tgt = flat_target(20);
  const BoundaryRegions good = bump_regions(src);
  auto fails_with = [&](BoundaryRegions r, const char* what) {
    CHECK_THROWS_WITH_AS(BoundaryOptimizer(src, tgt, r), doctest::Contains(what), InvalidArgument);
  };
  BoundaryRegions r = good;
  r.feature_faces.clear();
  fails_with(r, "Ωf is empty");
  r = good;
  r.feature_faces.push_back(src.num_faces());
  fails_with(r, "out of range");
  r = good;
  r.roi_faces = test::faces_within(src, 0.5);
  r.feature_faces = test::faces_within(src, 0.7);
  fails_with(r, "is not in the rough region");
  // The feature reaches Ω0's border along a spoke.
  r = good;
  for (int f : good.roi_faces) {
    const Eigen::Vector3d c = (src.V.row(src.F(f, 0)) + src.V.row(src.F(f, 1)) + src.V.row(src.F(f, 2))) / 3;
    if (c.x() > 0 && std::abs(c.y()) < 0.06) r.feature_faces.push_back(f);
  }
  fails_with(r, "touches Ω0's border");
  // A hole in the band: Ω0 has two borders.
  r = good;
  std::erase_if(r.roi_faces, [&](int f) {
    const Eigen::Vector3d c = (src.V.row(src.F(f, 0)) + src.V.row(src.F(f, 1)) + src.V.row(src.F(f, 2))) / 3;
    return (c - Eigen::Vector3d(0.6, 0, 0)).norm() < 0.1;
  });
  fails_with(r, "must be an annulus");
  // Ω1 with a hole is no disk.
  r = good;
  r.target_faces = test::faces_within(tgt, 1.4);
  const std::vector<int> middle = test::faces_within(tgt, 0.3);
  std::erase_if(r.target_faces, [&](int f) { return std::binary_search(middle.begin(), middle.end(), f); });
  fails_with(r, "Ω1 must be a disk");
  // A placement that puts ∂Ω0 off Ω1.
  const BoundaryOptimizer opt(src, tgt, good);
  Placement2D far = opt.suggested_placement();
  far.offset += Eigen::Vector2d(2.5, 0);
  CHECK_THROWS_WITH_AS(opt.optimize(far), doctest::Contains("maps outside the target region"), InvalidArgument);
  MergeOptions optimal_mode;
  optimal_mode.mode = MergeMode::OptimalBoundary;
  CHECK_THROWS_WITH_AS(Merger(src, optimal_mode), doctest::Contains("BoundaryOptimizer::merge()"), InvalidArgument);
}

// Pruning stops each Dijkstra beyond the cheapest loop found so far, and the searches from the
// cut's vertices run in parallel: neither may change the loop (ties go to the lowest cost, then
// the lowest start, whatever thread finds them).
// Errors that only the merge can find: the search needs ∂Ω0 inside Ω1, but the merge also needs
// the target faces under the boundary's image to keep a triangle off Ω1's border. The band's
// placement, grown about its centre until ∂Ω0's image comes that close, gives the error along
// ∂Ω0 while the optimal boundary, well inside, still merges.
TEST_CASE("optimal boundary: a merge whose boundary image reaches Ω1's border is a named error") {
  const geometry::TriMesh src = bump_with_ripples(20), tgt = flat_target(20);
  BoundaryRegions r = bump_regions(src);
  r.target_faces = test::faces_within(tgt, 1.2);
  const BoundaryOptimizer opt(src, tgt, r);
  const Placement2D suggested = opt.suggested_placement();
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (int v : opt.outer_loop()) centre += suggested(opt.source_uv().row(v).transpose());
  centre /= static_cast<double>(opt.outer_loop().size());
  bool reached = false;
  for (double grow = 1.0; grow < 1.5 && !reached; grow += 0.02) {
    Placement2D p = suggested;
    p.scale *= grow, p.offset = centre + grow * (suggested.offset - centre);
    OptimalBoundary b;
    try {
      b = opt.optimize(p);
    } catch (const InvalidArgument&) {
      break;  // ∂Ω0 left Ω1 first
    }
    try {
      (void)opt.merge(b, {}, true);
      continue;
    } catch (const InvalidArgument& e) {
      CAPTURE(grow);
      CHECK(std::string(e.what()).find("comes within one triangle of Ω1's border; move or shrink the band") !=
            std::string::npos);
      CHECK(seam_quality(tgt, opt.merge(b)).valid());
      reached = true;
    }
  }
  CHECK(reached);
}

TEST_CASE("optimal boundary: pruning and the thread count change nothing") {
  const BumpCase& c = bump_case();
  auto optimize = [&](bool prune, int threads) {
    OptimalBoundaryOptions o;
    o.prune = prune;
    const int before = omp_get_max_threads();
    omp_set_num_threads(threads);
    const OptimalBoundary b =
        BoundaryOptimizer(c.source, c.target, bump_regions(c.source), o).optimize(c.optimizer.suggested_placement());
    omp_set_num_threads(before);
    return b;
  };
  for (auto [prune, threads] : {std::pair{false, 2}, std::pair{true, 1}, std::pair{false, 1}}) {
    CAPTURE(prune);
    CAPTURE(threads);
    const OptimalBoundary b = optimize(prune, threads);
    CHECK(b.loop == c.boundary.loop);
    CHECK(b.energy == doctest::Approx(c.boundary.energy).epsilon(1e-12));
    CHECK(b.history.size() == c.boundary.history.size());
  }
}

TEST_CASE("optimal boundary: a feature in pieces or with a hole and bad options are named errors") {
  const geometry::TriMesh src = bump_with_ripples(20), tgt = flat_target(20);
  const BoundaryRegions good = bump_regions(src);
  auto fails_with = [&](BoundaryRegions r, const OptimalBoundaryOptions& o, const char* what) {
    CHECK_THROWS_WITH_AS(BoundaryOptimizer(src, tgt, r, o), doctest::Contains(what), InvalidArgument);
  };
  auto centre_of = [&](int f) -> Eigen::Vector3d {
    return (src.V.row(src.F(f, 0)) + src.V.row(src.F(f, 1)) + src.V.row(src.F(f, 2))) / 3;
  };
  BoundaryRegions r = good;  // two disks
  r.feature_faces.clear();
  for (int f : good.roi_faces)
    if ((centre_of(f) - Eigen::Vector3d(0.35, 0, 0)).norm() < 0.15 ||
        (centre_of(f) + Eigen::Vector3d(0.35, 0, 0)).norm() < 0.15)
      r.feature_faces.push_back(f);
  fails_with(r, {}, "must be connected with one boundary loop");
  r = good;  // an annulus: two boundary loops
  std::erase_if(r.feature_faces, [&](int f) { return centre_of(f).head<2>().norm() < 0.12; });
  fails_with(r, {}, "must be connected with one boundary loop");
  OptimalBoundaryOptions bad;
  bad.max_iterations = -1;
  fails_with(good, bad, "options out of range");
  bad = {};
  bad.max_exact_fill = 2;
  fails_with(good, bad, "options out of range");
  bad = {};
  bad.feature_clearance = -1;
  fails_with(good, bad, "options out of range");
  // A band about three rings wide has no loop six edges from Ωf.
  r = good;
  r.roi_faces = test::faces_within(src, test::kFeatureRadius + 0.3);
  OptimalBoundaryOptions far;
  far.feature_clearance = 6;
  fails_with(r, far, "Ω0 leaves no closed path around Ωf at least 6 edge(s) from it");
  far.feature_clearance = 1;
  CHECK_NOTHROW(BoundaryOptimizer(src, tgt, r, far));
}

// A torus with a disk cut away is a genus-1 feature with one boundary loop (thesis Fig. 3.14):
// the fill closes ∂Ωf, so the parameterization never sees the handle.
TEST_CASE("optimal boundary: a feature of genus 1 merges watertight") {
  const geometry::TriMesh torus = geometry::make_torus(64, 32, 1.0, 0.4);
  int top = 0;  // the outer equator's point at +x
  for (int v = 0; v < torus.num_vertices(); ++v)
    if (torus.V(v, 0) > torus.V(top, 0)) top = v;
  const geometry::ShortestPaths d = geometry::dijkstra(torus, {top});
  BoundaryRegions r;
  for (int f = 0; f < torus.num_faces(); ++f) {
    double dist = 0;
    for (int j = 0; j < 3; ++j) dist += d.distance[torus.F(f, j)] / 3;
    if (dist > 0.4) r.roi_faces.push_back(f);
    if (dist > 0.8) r.feature_faces.push_back(f);
  }
  // The target: a plane facing +x under the cut, its tessellation unrelated.
  geometry::TriMesh plane = flat_target(30);
  for (int v = 0; v < plane.num_vertices(); ++v)
    plane.V.row(v) = Eigen::RowVector3d(1.35, plane.V(v, 0), plane.V(v, 1));
  const BoundaryOptimizer opt(torus, plane, r);
  const OptimalBoundary b = opt.optimize(opt.suggested_placement());
  CHECK(b.energy < 0.5 * b.user_energy);  // 0.27 against 0.67
  const MergeResult m = opt.merge(b);
  const SeamQuality q = seam_quality(plane, m);
  CHECK(q.valid());
  CHECK(geometry::genus(m.mesh) == 1);
  CHECK(geometry::Connectivity(m.mesh).boundary_loops().size() == 1);  // the plane's border only
}

}  // namespace
}  // namespace lapis::mesh_merge
