// Every mesh of assets/external cut by planes across three axes at three heights, the part on the
// plane's positive side merged back onto the other in each mode: cases no other test was
// written with (scanned valences, obtuse triangles, thin necks, loops that pass close to
// themselves).
#include <cstdio>
#include <set>
#include <string_view>

#include <doctest/doctest.h>

#include <Eigen/Geometry>

#include "lapis/mesh_merge/metrics.h"
#include "merge_fixtures.h"

using namespace lapis;
using namespace lapis::mesh_merge;

namespace {

struct Outcome {
  int folds = 0, inherited = 0;
  double min_angle = 0, longest = 0, drift = 0, moved = 0;
  std::string mesh_problem;  // geometry::validate()'s summary: empty for a valid mesh
};

double mean_loop_edge(const TriMesh& m) {
  const auto& loop = geometry::Connectivity(m).boundary_loops().at(0);
  double perimeter = 0;
  for (size_t k = 0; k < loop.size(); ++k)
    perimeter += (m.V.row(loop[k]) - m.V.row(loop[(k + 1) % loop.size()])).norm();
  return perimeter / double(loop.size());
}

// Largest distance, over the source vertices outside a kept transition band, from where they
// end up to where they were before the cut, per bounding-box diagonal of the source.
double source_drift(const TriMesh& source, const MergeResult& r) {
  std::vector<char> band(static_cast<size_t>(r.mesh.num_vertices()), 0);
  for (int v : r.transition_vertices) band[static_cast<size_t>(v)] = 1;
  double largest = 0;
  for (int v = 0; v < source.num_vertices(); ++v) {
    const int m = r.source_map[static_cast<size_t>(v)];
    if (m >= 0 && !band[static_cast<size_t>(m)])
      largest = std::max(largest, (r.mesh.V.row(m) - source.V.row(v)).norm());
  }
  return largest / bbox_diagonal(source.V);
}

Outcome merge_back(const PlaneCut& cut, const std::vector<LoopPair>& pairs, const MergeOptions& o) {
  Outcome out;
  const MergeResult r = merge(cut.above, cut.below, pairs, o);
  const SeamQuality q = seam_quality(cut.below, r);
  out.folds = q.folded_seam_edges, out.inherited = q.inherited_folds;
  out.min_angle = q.min_strip_angle_deg;
  for (int f : r.strip_faces)
    for (int k = 0; k < 3; ++k)
      out.longest =
          std::max(out.longest, (r.mesh.V.row(r.mesh.F(f, k)) - r.mesh.V.row(r.mesh.F(f, (k + 1) % 3))).norm());
  out.longest /= mean_loop_edge(cut.below);
  out.drift = source_drift(cut.above, r);
  out.mesh_problem = geometry::validate(r.mesh).summary();
  // Everything valid() checks but the folds, which the caller checks against kStillFolding.
  CHECK(q.seam_boundary_edges == 0);
  CHECK(q.non_manifold_edges + q.non_manifold_vertices + q.degenerate_faces == 0);
  CHECK(q.max_target_displacement == 0.0);
  if (o.mode == MergeMode::Independent) {
    // §3.3.1: the same merge for any similarity of the source, the seam included.
    TriMesh moved = cut.above;
    const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    moved.V = ((2.5 * cut.above.V * R.transpose()).rowwise() + Eigen::RowVector3d(3, -1, 7)).eval();
    const MergeResult m = merge(moved, cut.below, pairs, o);
    out.moved =
        m.mesh.F == r.mesh.F ? (m.mesh.V - r.mesh.V).rowwise().norm().maxCoeff() / bbox_diagonal(r.mesh.V) : 1.0;
  }
  return out;
}

// Merges whose seam still folds (folded_seam_edges > 0, so valid() is false), which neither the
// strip's tiling, the flips nor the umbrella steps undo: in the independent one a target vertex
// one ring in lies almost on the loop's edge; in the transition ones the strip is folded
// already when zipped. Listed so that any other case folding fails; one of these no longer
// folding is reported.
struct Case {
  std::string_view mesh;
  int axis;
  double fraction;
  std::string_view mode;
  bool operator==(const Case&) const = default;
};
const Case kStillFolding[] = {
    {"mannequin-devil", 1, 0.5, "independent"},
    {"mannequin-devil", 0, 0.3, "keep target"},
    {"mannequin-devil", 1, 0.7, "keep source"},
    {"lion-head", 1, 0.7, "keep source"},
    {"lion-head", 1, 0.7, "keep target"},
    {"cactus", 2, 0.7, "keep target"},
    {"dino", 0, 0.5, "keep target"},
    {"diplodocus", 2, 0.3, "keep source"},
    {"diplodocus", 2, 0.3, "keep target"},
    {"man", 1, 0.5, "keep source"},
    {"man", 1, 0.5, "keep target"},
};

const std::string_view kModes[] = {"independent", "keep source", "keep target"};

MergeOptions options_for(std::string_view mode, const PlaneCut& cut, const std::vector<LoopPair>& pairs) {
  MergeOptions o;
  if (mode == "independent") return o;
  o.mode = MergeMode::Transition;
  o.transition.source_width = o.transition.target_width = suggested_transition_width(cut.above, cut.below, pairs);
  o.transition.keep = mode == "keep source" ? TransitionKeep::Source : TransitionKeep::Target;
  return o;
}

void check_case(const Case& c, const PlaneCut& cut, const std::vector<LoopPair>& pairs, bool same_loop) {
  CAPTURE(c.mesh);
  CAPTURE(c.axis);
  CAPTURE(c.fraction);
  CAPTURE(c.mode);
  Outcome out;
  REQUIRE_NOTHROW(out = merge_back(cut, pairs, options_for(c.mode, cut, pairs)));
  std::printf(
      "%-20s %d %.1f %-12s folds %2d (+%d inherited), min strip angle %7.3f, longest strip edge %5.2f loop edges, "
      "drift %8.2e, placement %8.2e %s\n",
      std::string(c.mesh).c_str(), c.axis, c.fraction, std::string(c.mode).c_str(), out.folds, out.inherited,
      out.min_angle, out.longest, out.drift, out.moved, out.mesh_problem.c_str());
  CHECK_MESSAGE(out.mesh_problem.empty(), out.mesh_problem);
  CHECK(out.moved < 1e-9);  // independent mode only; 0 otherwise
  // A part merged back where it was cut off stays there (the dino across z at 70% moves most,
  // by 9.2% of its diagonal). Where the plane cut left the two loops different, the part lands
  // turned by 15-70° (docs/mesh_merge.md#tests), which is not the zip's to fix.
  if (same_loop && c.mode == "independent") CHECK(out.drift < 0.1);
  const bool listed = std::find(std::begin(kStillFolding), std::end(kStillFolding), c) != std::end(kStillFolding);
  if (!listed) CHECK(out.folds == 0);
  if (listed && out.folds == 0) MESSAGE("no longer folds: remove it from kStillFolding");
}

}  // namespace

TEST_CASE("mesh_merge sweep: plane cuts of every external mesh merged back in each mode") {
  int cases = 0;
  for (const auto& entry : std::filesystem::directory_iterator(test::external("x").parent_path())) {
    if (entry.path().extension() != ".off") continue;
    const TriMesh m = geometry::read_mesh(entry.path());
    const std::string name = entry.path().stem().string();
    for (int axis = 0; axis < 3; ++axis)
      for (double fraction : {0.3, 0.5, 0.7}) {
        const Eigen::Vector3d lo = m.V.colwise().minCoeff(), hi = m.V.colwise().maxCoeff();
        const PlaneCut cut = cut_by_plane(m, lo + fraction * (hi - lo), Eigen::Vector3d::Unit(axis));
        const geometry::Connectivity above(cut.above), below(cut.below);
        // One loop pair per merge: cuts through several necks (legs, arms) are skipped.
        if (above.boundary_loops().size() != 1 || below.boundary_loops().size() != 1) continue;
        const int key = above.boundary_loops()[0][0];
        const auto at = std::find(cut.below_to_mesh.begin(), cut.below_to_mesh.end(), cut.above_to_mesh[key]);
        if (at == cut.below_to_mesh.end()) continue;
        const std::vector<LoopPair> pairs{LoopPair{{{key, static_cast<int>(at - cut.below_to_mesh.begin())}}}};
        std::set<int> loop_above, loop_below;
        for (int v : above.boundary_loops()[0]) loop_above.insert(cut.above_to_mesh[v]);
        for (int v : below.boundary_loops()[0]) loop_below.insert(cut.below_to_mesh[v]);
        for (std::string_view mode : kModes) {
          check_case(Case{name, axis, fraction, mode}, cut, pairs, loop_above == loop_below);
          ++cases;
        }
      }
  }
  MESSAGE(cases << " merges");
  CHECK(cases > 100);
}
