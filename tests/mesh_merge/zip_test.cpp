// The seam's clean-up after zipping: folded strip edges unfolded by moving only what may move.
#include <numbers>

#include <doctest/doctest.h>

#include "lapis/mesh_merge/metrics.h"
#include "lapis/mesh_merge/zip.h"
#include "merge_fixtures.h"

using namespace lapis;
using namespace lapis::mesh_merge;

TEST_CASE("mesh_merge: unfolding a spiked seam moves only the listed vertices and leaves no fold") {
  const TriMesh src = test::dome(), tgt = test::body();
  MergeOptions o;
  o.smooth_iterations = 0;
  MergeResult r = merge(src, tgt, test::dome_on_body(src, tgt), o);
  REQUIRE(seam_quality(tgt, r).folded_seam_edges == 0);
  // Push one source loop vertex far down through the target: a spike whose strip triangles
  // fold against the target beside them.
  const int spike = r.seam_vertices.back();
  r.mesh.V(spike, 2) -= 0.5;
  const int folded = seam_quality(tgt, r).folded_seam_edges;
  REQUIRE(folded > 0);
  const Vertices before = r.mesh.V;
  const geometry::Faces faces_before = r.mesh.F;
  const std::vector<int> movable = seam_band(r.mesh, r.seam_vertices, 1);
  CHECK(unfold_seam(r.mesh, r.strip_faces, movable) == 0);
  CHECK(seam_quality(tgt, r).folded_seam_edges == 0);
  std::vector<char> may(static_cast<size_t>(r.mesh.num_vertices()), 0);
  for (int v : movable) may[v] = 1;
  for (int v = 0; v < r.mesh.num_vertices(); ++v)
    if (!may[v]) REQUIRE(r.mesh.V.row(v) == before.row(v));
  // With nothing movable only the strip's diagonals may flip: the spike stays, and what is left
  // is reported.
  r.mesh.V = before;
  r.mesh.F = faces_before;
  const int left = unfold_seam(r.mesh, r.strip_faces, {});
  CHECK(left > 0);
  CHECK(left <= folded);
  CHECK(left == seam_quality(tgt, r).folded_seam_edges);
  CHECK(r.mesh.V == before);
}

namespace {

// Two strip triangles on the quad (0, 1, 2, 3) sharing the diagonal (0, 2), and one more
// triangle beside the quad's edge (0, 1) (face 2), which is not part of the strip.
TriMesh quad(const Eigen::Vector3d& far_corner) {
  TriMesh m;
  m.V.resize(5, 3);
  m.V << 0, 0, 0, 1, 0, 0, far_corner.x(), far_corner.y(), far_corner.z(), 0, 1, 0, 0.5, -1, 0;
  m.F = geometry::Faces{{0, 1, 2}, {0, 2, 3}, {0, 4, 1}};
  return m;
}

double smallest_angle_deg(const TriMesh& m, const std::vector<int>& faces) {
  double smallest = 180;
  for (int f : faces)
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d p = m.V.row(m.F(f, k)).transpose();
      const Eigen::Vector3d a = m.V.row(m.F(f, (k + 1) % 3)).transpose() - p,
                            b = m.V.row(m.F(f, (k + 2) % 3)).transpose() - p;
      smallest = std::min(smallest, std::atan2(a.cross(b).norm(), a.dot(b)) * 180 / std::numbers::pi);
    }
  return smallest;
}

Eigen::Vector3d unit_normal(const TriMesh& m, int f) {
  const Eigen::Vector3d a = m.V.row(m.F(f, 0)).transpose();
  return (m.V.row(m.F(f, 1)).transpose() - a).cross(m.V.row(m.F(f, 2)).transpose() - a).normalized();
}

}  // namespace

TEST_CASE("mesh_merge: a thin pair of strip triangles takes the other diagonal") {
  // A long thin rhombus: the long diagonal (0, 2) makes two 5.7° needles, the short one
  // (1, 3) triangles of 11.4° and more.
  TriMesh m = quad({2, 0, 0});
  m.V.row(1) << 1, -0.1, 0;
  m.V.row(3) << 1, 0.1, 0;
  const double before = smallest_angle_deg(m, {0, 1});
  CHECK(flip_thin_diagonals(m, {0, 1}) == 1);
  CHECK(smallest_angle_deg(m, {0, 1}) > before + 5);
  CHECK(geometry::validate(m).ok());
  CHECK(m.F.row(2) == Eigen::RowVector3i(0, 4, 1));  // the face beside the strip is untouched

  // A square: both diagonals give 45°, a tie, which stays (a turned copy must tile alike).
  TriMesh square = quad({1, 1, 0});
  CHECK(flip_thin_diagonals(square, {0, 1}) == 0);

  // The same rhombus beside a fold (face 2 turned over onto it): folds are unfold_seam's, and
  // a flip there could move the fold where the metrics no longer see it as the target's own.
  TriMesh beside_fold = quad({2, 0, 0});
  beside_fold.V.row(1) << 1, -0.1, 0;
  beside_fold.V.row(3) << 1, 0.1, 0;
  beside_fold.V.row(4) << 0.5, 1, 0;
  REQUIRE(unit_normal(beside_fold, 0).dot(unit_normal(beside_fold, 2)) < -0.5);
  const geometry::Faces faces = beside_fold.F;
  CHECK(flip_thin_diagonals(beside_fold, {0, 1}) == 0);
  CHECK(beside_fold.F == faces);
}

TEST_CASE("mesh_merge: real meshes: slivers in transition strips are flipped out") {
  // The bunny cut across z at 70%, merged back keeping the target's band: the strip tiled
  // between the source's rim and the kept band's next ring had a 0.09° triangle.
  const TriMesh m = geometry::read_mesh(test::external("bunny00"));
  const Eigen::Vector3d lo = m.V.colwise().minCoeff(), hi = m.V.colwise().maxCoeff();
  const PlaneCut cut = cut_by_plane(m, lo + 0.7 * (hi - lo), Eigen::Vector3d::UnitZ());
  const int key = geometry::Connectivity(cut.above).boundary_loops().at(0)[0];
  const auto at = std::find(cut.below_to_mesh.begin(), cut.below_to_mesh.end(), cut.above_to_mesh[key]);
  const std::vector<LoopPair> pairs{LoopPair{{{key, static_cast<int>(at - cut.below_to_mesh.begin())}}}};
  MergeOptions o;
  o.mode = MergeMode::Transition;
  o.transition.keep = TransitionKeep::Target;
  o.transition.source_width = o.transition.target_width = suggested_transition_width(cut.above, cut.below, pairs);
  const MergeResult r = merge(cut.above, cut.below, pairs, o);
  const SeamQuality q = seam_quality(cut.below, r);
  MESSAGE("smallest strip angle " << q.min_strip_angle_deg);
  CHECK(q.min_strip_angle_deg > 3);
  CHECK(q.valid());
  CHECK(geometry::validate(r.mesh).ok());
}
