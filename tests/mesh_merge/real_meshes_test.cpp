// Real meshes from assets/external (scripts/setup extracts them from libcgal-demo): parts cut
// off one mesh by a plane and merged onto another, as in the thesis' head-onto-body examples.
#include <numbers>
#include <set>

#include <doctest/doctest.h>

#include <Eigen/Geometry>

#include "lapis/geometry/dijkstra.h"
#include "lapis/mesh_merge/metrics.h"
#include "lapis/mesh_merge/optimal_boundary.h"
#include "merge_fixtures.h"

using namespace lapis;
using namespace lapis::mesh_merge;

namespace {

TriMesh load(const std::string& name) {
  const auto path = test::external(name);
  REQUIRE_MESSAGE(std::filesystem::exists(path), path.string() << " missing: run scripts/setup");
  return geometry::read_mesh(path);
}

// The loop vertex of the only boundary loop of m with the largest coordinate `axis`.
int extreme_loop_vertex(const TriMesh& m, int axis) {
  const geometry::Connectivity conn(m);
  REQUIRE(conn.boundary_loops().size() == 1);
  const auto& loop = conn.boundary_loops()[0];
  return *std::max_element(loop.begin(), loop.end(), [&](int a, int b) { return m.V(a, axis) < m.V(b, axis); });
}

MergeResult check_real_merge(const TriMesh& head, const TriMesh& body, int key_axis) {
  const std::vector<LoopPair> pairs{
      LoopPair{{{extreme_loop_vertex(head, key_axis), extreme_loop_vertex(body, key_axis)}}}};
  const MergeResult r = merge(head, body, pairs);
  const SeamQuality q = seam_quality(body, r);
  const DetailPreservation d = detail_preservation(head, r);
  MESSAGE(head.num_vertices() << " source vertices onto " << body.num_vertices() << ": " << r.timings.total_ms
                              << " ms, min strip angle " << q.min_strip_angle_deg << ", seam dihedral mean "
                              << q.seam_dihedral_mean_deg << " (target p95 " << q.target_dihedral_p95_deg
                              << "), residual " << d.laplacian_residual << ", max distance " << d.max_distance);
  CHECK(q.valid());
  CHECK(q.max_target_displacement == 0.0);
  // Greedy zipping of two loops with different vertex densities leaves thin triangles; the
  // bound catches a collapsed strip, not a poor one.
  CHECK(q.min_strip_angle_deg > 0.1);
  CHECK(q.seam_dihedral_mean_deg < q.target_dihedral_p95_deg);
  // The parts' necks differ in shape, so the source bends near the seam; its details must
  // survive (residual) and its overall shape stay recognizable (distance after alignment).
  CHECK(d.laplacian_residual < 1.0);
  CHECK(d.max_distance < 0.25);
  CHECK(geometry::validate(r.mesh).ok());
  return r;
}

}  // namespace

TEST_CASE("mesh_merge: real meshes: the mannequin's head onto the man's body") {
  // The devil bust's head and neck (40 units tall; cut at z = -14 where the neck rim is round
  // like the man's, not under the chin) onto the man (1 unit tall) cut at the
  // neck: different scales, positions and neck shapes.
  const PlaneCut devil = cut_by_plane(load("mannequin-devil"), {0, 0, -14.0}, {0, 0, 1});
  const PlaneCut man = cut_by_plane(load("man"), {0, 0, 0.36}, {0, 0, 1});
  const MergeResult r = check_real_merge(devil.above, man.below, 0);
  // Left for the figure docs/images/merge_devil_on_man.png (scripts/render_mesh.py).
  geometry::write_obj(std::filesystem::temp_directory_path() / "lapis_merge_devil_head_on_man.obj", r.mesh);
}

TEST_CASE("mesh_merge: real meshes: transition regions merge the mannequin's head onto the man's body") {
  const PlaneCut devil = cut_by_plane(load("mannequin-devil"), {0, 0, -14.0}, {0, 0, 1});
  const PlaneCut man = cut_by_plane(load("man"), {0, 0, 0.36}, {0, 0, 1});
  const std::vector<LoopPair> pairs{
      LoopPair{{{extreme_loop_vertex(devil.above, 0), extreme_loop_vertex(man.below, 0)}}}};
  MergeOptions o;
  o.mode = MergeMode::Transition;
  o.transition.source_width = o.transition.target_width = suggested_transition_width(devil.above, man.below, pairs);
  for (TransitionKeep keep : {TransitionKeep::Source, TransitionKeep::Target}) {
    o.transition.keep = keep;
    const MergeResult r = merge(devil.above, man.below, pairs, o);
    const SeamQuality q = seam_quality(man.below, r);
    MESSAGE("keep " << (keep == TransitionKeep::Source ? "source" : "target") << ": " << r.timings.total_ms << " ms, "
                    << r.transition_vertices.size() << " band vertices, seam dihedral mean "
                    << q.seam_dihedral_mean_deg);
    CHECK(q.valid());
    CHECK(q.max_target_displacement == 0.0);
    CHECK(geometry::validate(r.mesh).ok());
    CHECK(!r.transition_vertices.empty());
  }
}

namespace {

// A plane cut of `name` across `axis` at `fraction` of the extent along it, the part above
// merged back onto the part below, keyed at the first vertex of the upper part's loop.
struct SelfCut {
  PlaneCut cut;
  std::vector<LoopPair> pairs;
};

SelfCut self_cut(const std::string& name, double fraction, int axis = 2) {
  const TriMesh m = load(name);
  const Eigen::Vector3d lo = m.V.colwise().minCoeff(), hi = m.V.colwise().maxCoeff();
  SelfCut s{cut_by_plane(m, lo + fraction * (hi - lo), Eigen::Vector3d::Unit(axis)), {}};
  const geometry::Connectivity above(s.cut.above);
  REQUIRE(above.boundary_loops().size() == 1);
  const int key = above.boundary_loops()[0][0];
  const auto& below = s.cut.below_to_mesh;
  const auto at = std::find(below.begin(), below.end(), s.cut.above_to_mesh[key]);
  REQUIRE(at != below.end());
  s.pairs = {LoopPair{{{key, static_cast<int>(at - below.begin())}}}};
  return s;
}

// Plane cuts (mesh, height) whose target loop passes within one triangle of itself.
const std::pair<const char*, double> kLoopsNearThemselves[] = {
    {"cactus", 0.3}, {"double-torus-example", 0.7}, {"bunny00", 0.5}};

// The target's band next to the loop is not an annulus here: removing it (the thesis' zip)
// leaves several inner loops or cuts a piece off, which zip_seams() reported as an error.
void check_zipped_without_band(const TriMesh& source, const SelfCut& s, MergeMode mode) {
  MergeOptions o;
  o.mode = mode;
  const MergeResult r = merge(source, s.cut.below, s.pairs, o);
  const SeamQuality q = seam_quality(s.cut.below, r);
  CHECK(q.valid());
  CHECK(geometry::validate(r.mesh).ok());
  CHECK(std::count(r.target_map.begin(), r.target_map.end(), -1) == 0);  // nothing of the target removed
  CHECK(geometry::connected_components(r.mesh).count == 1);
  CHECK(q.max_target_displacement == 0.0);
  CHECK(q.min_strip_angle_deg > 1.0);
  // As where the band is removed: a coarse source (73 vertices for the double torus) bends
  // by up to 5.5% of its diagonal to meet the loop, a fine one by well under 1%.
  CHECK(detail_preservation(source, r).max_distance < 0.06);
}

}  // namespace

TEST_CASE("mesh_merge: real meshes: a target loop within one triangle of itself is zipped without cutting the target" *
          doctest::test_suite("slow")) {
  for (const auto& [name, fraction] : kLoopsNearThemselves) {
    CAPTURE(name);
    const SelfCut s = self_cut(name, fraction);
    for (MergeMode mode : {MergeMode::Independent, MergeMode::Dependent})
      check_zipped_without_band(s.cut.above, s, mode);
  }
  // A finer source: its loop has a vertex between every two of the target's, so the zip
  // splits the target's faces on the loop instead of only welding the loops.
  const SelfCut cactus = self_cut("cactus", 0.3);
  check_zipped_without_band(geometry::midpoint_subdivide(cactus.cut.above, 1), cactus, MergeMode::Independent);
}

namespace {

// Largest and mean distance, over the source vertices outside the kept transition band, from
// where they end up to where they were in the uncut mesh, per bounding-box diagonal.
std::pair<double, double> source_drift(const TriMesh& source, const MergeResult& r) {
  std::vector<char> band(static_cast<size_t>(r.mesh.num_vertices()), 0);
  for (int v : r.transition_vertices) band[static_cast<size_t>(v)] = 1;
  double largest = 0, sum = 0;
  int count = 0;
  for (int v = 0; v < source.num_vertices(); ++v) {
    const int m = r.source_map[static_cast<size_t>(v)];
    if (m < 0 || band[static_cast<size_t>(m)]) continue;
    const double d = (r.mesh.V.row(m) - source.V.row(v)).norm();
    largest = std::max(largest, d), sum += d, ++count;
  }
  REQUIRE(count > 0);
  const double diagonal = bbox_diagonal(source.V);
  return {largest / diagonal, sum / count / diagonal};
}

double loop_diameter(const TriMesh& m) {
  const geometry::Connectivity conn(m);
  return loop_perimeter(m.V, conn.boundary_loops().at(0)) / std::numbers::pi;
}

}  // namespace

TEST_CASE("mesh_merge: real meshes: transition regions leave a part merged back where it was cut off") {
  // §3.3.3 solves "with the same boundary condition as before": the source loop onto the target
  // loop. Constrained onto the target band's rim instead, the mannequin's upper half drifted by
  // 25% of the diagonal on average (it sank, shrank and tilted).
  const SelfCut s = self_cut("mannequin-devil", 0.5);
  MergeOptions o;
  o.mode = MergeMode::Transition;
  o.transition.source_width = o.transition.target_width = suggested_transition_width(s.cut.above, s.cut.below, s.pairs);
  for (TransitionKeep keep : {TransitionKeep::Source, TransitionKeep::Target}) {
    CAPTURE(static_cast<int>(keep));
    o.transition.keep = keep;
    const MergeResult r = merge(s.cut.above, s.cut.below, s.pairs, o);
    const auto [largest, mean] = source_drift(s.cut.above, r);
    MESSAGE("keep " << (keep == TransitionKeep::Source ? "source" : "target") << ": drift mean " << mean << ", largest "
                    << largest << " of the diagonal");
    CHECK(mean < 2e-3);
    CHECK(largest < 1e-2);
    CHECK(geometry::validate(r.mesh).ok());
    CHECK(seam_quality(s.cut.below, r).max_target_displacement == 0.0);
  }
}

TEST_CASE("mesh_merge: real meshes: the suggested transition width gives bands the merge accepts") {
  // A fifth of the loop's diameter reaches past the mannequin's neck on the lower half: the band
  // is not an annulus. The suggestion shrinks until both bands are.
  const SelfCut s = self_cut("mannequin-devil", 0.5);
  MergeOptions o;
  o.mode = MergeMode::Transition;
  o.transition.source_width = o.transition.target_width = 0.2 * loop_diameter(s.cut.below);
  CHECK_THROWS_WITH_AS(merge(s.cut.above, s.cut.below, s.pairs, o), doctest::Contains("is not an annulus"),
                       InvalidArgument);
  const double w = suggested_transition_width(s.cut.above, s.cut.below, s.pairs);
  CHECK(w > 0);
  CHECK(w < o.transition.target_width);
  o.transition.source_width = o.transition.target_width = w;
  CHECK_NOTHROW(merge(s.cut.above, s.cut.below, s.pairs, o));

  // Where no width works (a target of one triangle: every band covers it), the suggestion
  // says why.
  TriMesh triangle;
  triangle.V = s.cut.below.V.topRows(3);
  triangle.F = geometry::Faces{{0, 1, 2}};
  const int key = s.pairs[0].keys[0].source;
  CHECK_THROWS_WITH_AS(suggested_transition_width(s.cut.above, triangle, {LoopPair{{{key, 0}}}}),
                       doctest::Contains("no transition width down to"), InvalidArgument);
}

TEST_CASE("mesh_merge: real meshes: the merge does not depend on where the source was placed") {
  // §3.3.1: configuration-independent merging gives the same surface for any similarity of the
  // source. The mannequin's head is held only at its neck, and Eq. 2.8's normal matrix is
  // ill-conditioned enough (~1e11) that one back-substitution left 2e-5 of the diagonal of
  // rounding, reshuffled by any change of the input; the solve's refinement step removes it.
  // The plane cut's loop points are exactly collinear in the frame they were cut in and not in
  // any other, which changed the strip's tiling (37 faces) until flat triangles were told apart
  // by a tolerance.
  const PlaneCut devil = cut_by_plane(load("mannequin-devil"), {0, 0, -14.0}, {0, 0, 1});
  const PlaneCut man = cut_by_plane(load("man"), {0, 0, 0.36}, {0, 0, 1});
  const std::vector<LoopPair> pairs{
      LoopPair{{{extreme_loop_vertex(devil.above, 0), extreme_loop_vertex(man.below, 0)}}}};
  const MergeResult a = merge(devil.above, man.below, pairs);
  TriMesh moved = devil.above;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  moved.V = ((2.5 * devil.above.V * R.transpose()).rowwise() + Eigen::RowVector3d(3, -1, 7)).eval();
  const MergeResult b = merge(moved, man.below, pairs);
  REQUIRE(a.source_deformed.rows() == b.source_deformed.rows());
  const double difference =
      (a.source_deformed - b.source_deformed).rowwise().norm().maxCoeff() / bbox_diagonal(a.mesh.V);
  MESSAGE("largest difference of the solved source / diagonal: " << difference);
  CHECK(difference < 1e-9);
  REQUIRE(a.mesh.F == b.mesh.F);
  const double merged = (a.mesh.V - b.mesh.V).rowwise().norm().maxCoeff() / bbox_diagonal(a.mesh.V);
  MESSAGE("largest difference of the merged mesh / diagonal: " << merged);
  CHECK(merged < 1e-9);
}

TEST_CASE("mesh_merge: real meshes: a fold the strip's tiling left is flipped out") {
  // The dino cut at 70% of its height: the strip tiled on the unsmoothed loops left a zig-zag
  // across a fold (two folded edges, 146°) that umbrella steps alone cannot undo; flipping the
  // diagonals first lets them.
  const SelfCut s = self_cut("dino", 0.7);
  const MergeResult r = merge(s.cut.above, s.cut.below, s.pairs);
  const SeamQuality q = seam_quality(s.cut.below, r);
  MESSAGE("folded edges " << q.folded_seam_edges << ", largest seam dihedral " << q.seam_dihedral_max_deg);
  CHECK(q.folded_seam_edges == 0);
  CHECK(q.valid());
  CHECK(geometry::validate(r.mesh).ok());
}

TEST_CASE("mesh_merge: real meshes: the strip does not fan across the loop to avoid a fold") {
  // The mannequin cut across x at 70%: the strip with the fewest folds, at any length, had
  // fans from one inner vertex reaching 14 loop edges across the loop, and two folds after
  // smoothing. The tiling now keeps within a few steps of the shortest one.
  const SelfCut s = self_cut("mannequin-devil", 0.7, 0);
  const MergeResult r = merge(s.cut.above, s.cut.below, s.pairs);
  const SeamQuality q = seam_quality(s.cut.below, r);
  const geometry::Connectivity below(s.cut.below);
  const auto& loop = below.boundary_loops().at(0);
  double perimeter = 0, longest = 0;
  for (size_t k = 0; k < loop.size(); ++k)
    perimeter += (s.cut.below.V.row(loop[k]) - s.cut.below.V.row(loop[(k + 1) % loop.size()])).norm();
  for (int f : r.strip_faces)
    for (int k = 0; k < 3; ++k)
      longest = std::max(longest, (r.mesh.V.row(r.mesh.F(f, k)) - r.mesh.V.row(r.mesh.F(f, (k + 1) % 3))).norm());
  const double in_loop_edges = longest / (perimeter / double(loop.size()));
  MESSAGE("longest strip edge " << in_loop_edges << " loop edges, folds " << q.folded_seam_edges);
  CHECK(in_loop_edges < 8);
  CHECK(q.valid());
  CHECK(geometry::validate(r.mesh).ok());
}

TEST_CASE("mesh_merge: real meshes: an inner loop through one vertex twice is not bridged") {
  // The diplodocus cut across z at 30%: one target vertex touches the loop in two separate
  // sectors, so the ring's inner loop passes through it twice. Bridged as a loop, it gave a
  // non-manifold edge (and after the flips, two faces on the same corners); now the pair is
  // zipped without removing the ring. A transition that keeps the target meets the same pinch
  // in its zip, which now names it: the edges there are split and the zip runs again.
  const SelfCut s = self_cut("diplodocus", 0.3);
  const MergeResult r = merge(s.cut.above, s.cut.below, s.pairs);
  const SeamQuality q = seam_quality(s.cut.below, r);
  CHECK(q.valid());
  CHECK(geometry::validate(r.mesh).ok());
  CHECK(std::count(r.target_map.begin(), r.target_map.end(), -1) == 0);  // zipped without a band
  MergeOptions o;
  o.mode = MergeMode::Transition;
  o.transition.keep = TransitionKeep::Target;
  o.transition.source_width = o.transition.target_width = suggested_transition_width(s.cut.above, s.cut.below, s.pairs);
  const MergeResult t = merge(s.cut.above, s.cut.below, s.pairs, o);
  const geometry::ValidationReport report = geometry::validate(t.mesh);
  CHECK(report.non_manifold_edges.empty());
  CHECK(report.misoriented_edges.empty());
}

TEST_CASE("mesh_merge: real meshes: a fold the target already had is not the seam's") {
  // The man cut across y at half its width: the scan folds (a 167° spike) on an edge of the
  // ring next to the loop, and the strip face that replaces the ring's face there folds the
  // same way against the target's face beyond it.
  const SelfCut s = self_cut("man", 0.5, 1);
  const MergeResult r = merge(s.cut.above, s.cut.below, s.pairs);
  const SeamQuality q = seam_quality(s.cut.below, r);
  CHECK(q.inherited_folds == 1);
  CHECK(q.folded_seam_edges == 0);
  CHECK(q.valid());
  CHECK(q.seam_dihedral_max_deg > geometry::kFoldedDihedralDeg);  // still there, and still reported
}

namespace {

// Faces whose three corners lie within `fraction` of the bounding-box diagonal (edge paths) of
// the vertex extreme along `axis` (sign +1: largest coordinate).
std::vector<int> geodesic_disk(const TriMesh& m, int axis, double sign, double fraction) {
  int centre = 0;
  for (int v = 0; v < m.num_vertices(); ++v)
    if (sign * m.V(v, axis) > sign * m.V(centre, axis)) centre = v;
  const geometry::ShortestPaths d = geometry::dijkstra(m, {centre});
  const double radius = fraction * (m.V.colwise().maxCoeff() - m.V.colwise().minCoeff()).norm();
  std::vector<int> faces;
  for (int f = 0; f < m.num_faces(); ++f)
    if (std::max({d.distance[m.F(f, 0)], d.distance[m.F(f, 1)], d.distance[m.F(f, 2)]}) < radius) faces.push_back(f);
  return faces;
}

}  // namespace

// Cross-object cases where the merge along the optimal boundary first folded its seam (the
// dragon onto the diplodocus) or the suggested placement let the hole reach Ω1's border (the
// camel onto the elephant). The camel's rough region reaches 12% of its diagonal: at 10% the
// band is about two rings wide, and the held feature one ring from the optimal loop folds one
// strip edge (163°; seam_quality() reports it).
TEST_CASE("mesh_merge: real meshes: optimal boundaries of one mesh's part on another") {
  struct Case {
    const char* source;
    int axis;
    double sign, feature, rough;
    const char* target;
    int target_axis;
    double target_sign, region;
  };
  for (const Case& c :
       {Case{"camel", 0, 1, 0.05, 0.12, "elephant", 1, 1, 0.15}, Case{"dino", 2, 1, 0.04, 0.08, "cactus", 0, 1, 0.1},
        Case{"ChineseDragon-10kv", 0, 1, 0.05, 0.1, "diplodocus", 1, 1, 0.15},
        Case{"man", 1, 1, 0.03, 0.06, "mannequin-devil", 1, 1, 0.1}}) {
    const std::string name = c.source;
    CAPTURE(name);
    const TriMesh src = load(c.source), tgt = load(c.target);
    BoundaryRegions regions;
    regions.feature_faces = geodesic_disk(src, c.axis, c.sign, c.feature);
    regions.roi_faces = geodesic_disk(src, c.axis, c.sign, c.rough);
    regions.target_faces = geodesic_disk(tgt, c.target_axis, c.target_sign, c.region);
    const BoundaryOptimizer opt(src, tgt, regions);
    const OptimalBoundary b = opt.optimize(opt.suggested_placement());
    MESSAGE(std::string(c.source) << " onto " << std::string(c.target) << ": E " << b.energy << " against "
                                  << b.user_energy << " along ∂Ω0, " << b.history.size() << " iterations ("
                                  << b.stopped_by << ")");
    CHECK(b.energy < 0.8 * b.user_energy);
    const MergeResult optimal = opt.merge(b), user = opt.merge(b, {}, true);
    CHECK(seam_quality(tgt, optimal).valid());
    CHECK(seam_quality(tgt, user).valid());
    // Each merged source part, aligned to its original, lies closer to it along the optimal loop
    // (0.0071 / 0.0022 / 1.6e-5 / 0.0034 against 0.011 / 0.0024 / 2.1e-5 / 0.0038 of its
    // diagonal).
    const DetailPreservation dp = detail_preservation(src, optimal), du = detail_preservation(src, user);
    MESSAGE("  detail: max distance " << dp.max_distance << " against " << du.max_distance << " along ∂Ω0");
    CHECK(dp.max_distance <= du.max_distance);
    // Ωf held by a shared gradient (the default) moves by one similarity along either loop, to
    // 0.04–0.2% of its size, where left free it bends by 10–22% (7–15% along ∂Ω0). The optimal
    // loop keeps one edge off ∂Ωf (feature_clearance); on ∂Ωf itself the held feature's border
    // went onto the target (14–34%).
    MergeOptions free;
    free.hold_feature = false;
    const MergeResult optimal_free = opt.merge(b, free), user_free = opt.merge(b, free, true);
    const std::vector<int> feature = geometry::vertices_of_faces(src, regions.feature_faces);
    const double held_optimal = feature_distortion(src, optimal, feature),
                 held_user = feature_distortion(src, user, feature),
                 free_optimal = feature_distortion(src, optimal_free, feature),
                 free_user = feature_distortion(src, user_free, feature);
    MESSAGE("  feature distortion: held " << held_optimal << " / " << held_user << ", free " << free_optimal << " / "
                                          << free_user << " (optimal loop / ∂Ω0)");
    CHECK(held_optimal < 0.005);
    CHECK(held_optimal < 0.05 * free_optimal);
    CHECK(held_user < 0.005);
    const std::set<int> near(opt.inner_loop().begin(), opt.inner_loop().end());
    for (int v : b.loop) CHECK(near.count(v) == 0);
  }
}

TEST_CASE("mesh_merge: real meshes: transition regions next to a target loop within one triangle of itself" *
          doctest::test_suite("slow")) {
  // One ring of faces next to these loops is not an annulus: the loop reaches back to itself
  // within a triangle. No band width was accepted until the edges there are split.
  for (const auto& [name, fraction] : kLoopsNearThemselves) {
    CAPTURE(name);
    const SelfCut s = self_cut(name, fraction);
    MergeOptions o;
    o.mode = MergeMode::Transition;
    o.transition.source_width = o.transition.target_width =
        suggested_transition_width(s.cut.above, s.cut.below, s.pairs);
    for (TransitionKeep keep : {TransitionKeep::Source, TransitionKeep::Target}) {
      CAPTURE(static_cast<int>(keep));
      o.transition.keep = keep;
      const MergeResult r = merge(s.cut.above, s.cut.below, s.pairs, o);
      const SeamQuality q = seam_quality(s.cut.below, r);
      const auto [largest, mean] = source_drift(s.cut.above, r);
      MESSAGE("width " << o.transition.target_width << ": folds " << q.folded_seam_edges << ", smallest strip angle "
                       << q.min_strip_angle_deg << ", drift mean " << mean << ", largest " << largest);
      CHECK(q.valid());
      CHECK(geometry::validate(r.mesh).ok());
      CHECK(geometry::connected_components(r.mesh).count == 1);
      CHECK(q.max_target_displacement == 0.0);
      CHECK(mean < 5e-3);  // the part stays where it was cut off
      CHECK(largest < 0.03);
      CHECK(r.target_map.size() == static_cast<size_t>(s.cut.below.num_vertices()));
      CHECK(r.source_map.size() == static_cast<size_t>(s.cut.above.num_vertices()));
    }
  }
}
