// Suggested key correspondences: a part cut off a real mesh goes back the way it was placed,
// whatever its frame; a key half the loop away turns it face-down, which the turn metric shows.
#include <numbers>

#include <doctest/doctest.h>

#include <Eigen/Geometry>

#include "lapis/mesh_merge/cut.h"
#include "lapis/mesh_merge/merge_setup.h"
#include "lapis/mesh_merge/metrics.h"
#include "lapis/mesh_merge/suggest_key.h"
#include "merge_fixtures.h"

using namespace lapis;
using namespace lapis::mesh_merge;

namespace {

struct CutParts {
  PlaneCut cut;
  std::vector<int> source_loop, target_loop;  // the only loop of each part
};

// A mesh cut by a tilted plane through the point a fraction `f` up its bounding box along
// `axis`; empty loops unless each part has exactly one loop and they match (no island dropped).
CutParts tilted_cut(const std::string& name, int axis, double f) {
  const auto path = test::external(name);
  REQUIRE_MESSAGE(std::filesystem::exists(path), path.string() << " missing: run scripts/setup");
  const TriMesh m = geometry::read_mesh(path);
  const Eigen::Vector3d lo = m.V.colwise().minCoeff(), hi = m.V.colwise().maxCoeff();
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  n[axis] = 1, n[(axis + 1) % 3] = 0.3;
  CutParts p{cut_by_plane(m, lo + f * (hi - lo), n), {}, {}};
  const geometry::Connectivity above(p.cut.above), below(p.cut.below);
  if (above.boundary_loops().size() == 1 && below.boundary_loops().size() == 1 &&
      above.boundary_loops()[0].size() == below.boundary_loops()[0].size())
    p.source_loop = above.boundary_loops()[0], p.target_loop = below.boundary_loops()[0];
  return p;
}

// The man cut across the body: one loop each side, 235 vertices, far from round.
CutParts man_cut() {
  CutParts p = tilted_cut("man", 0, 0.5);
  REQUIRE(p.source_loop.size() == 235);
  return p;
}

Eigen::Matrix4d similarity(double scale, const Eigen::Matrix3d& R, const Eigen::Vector3d& t) {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = scale * R;
  T.topRightCorner<3, 1>() = t;
  return T;
}

TriMesh transformed(TriMesh m, const Eigen::Matrix4d& T) {
  for (int v = 0; v < m.num_vertices(); ++v)
    m.V.row(v) = (T.topLeftCorner<3, 3>() * m.V.row(v).transpose() + T.topRightCorner<3, 1>()).transpose();
  return m;
}

}  // namespace

TEST_CASE(
    "mesh_merge: suggest_key pairs the vertices a plane cut separated, on real meshes, in any frame placed back") {
  int cuts = 0;
  for (std::string name : {"camel", "man", "elephant", "lion", "dino", "bunny00", "armadillo", "diplodocus", "cactus"})
    for (int axis = 0; axis < 3; ++axis)
      for (double f : {0.3, 0.5, 0.7}) {
        CutParts p;
        try {
          p = tilted_cut(name, axis, f);
        } catch (const InvalidArgument&) {
          continue;  // a side left empty
        }
        if (p.source_loop.empty()) continue;  // islands dropped: the loops differ
        CAPTURE(name);
        CAPTURE(axis);
        CAPTURE(f);
        ++cuts;
        const KeySuggestion s =
            suggest_key(p.cut.above, Eigen::Matrix4d::Identity(), p.source_loop, p.cut.below, p.target_loop);
        // The loops are one edge path: the key joins a vertex to itself.
        CHECK(p.cut.above_to_mesh[static_cast<size_t>(s.key.source)] ==
              p.cut.below_to_mesh[static_cast<size_t>(s.key.target)]);
        CHECK(s.residual < 0.05);
        CHECK(s.decisive());
        // Stored turned, scaled and moved, placed back by the inverse: the same key.
        const Eigen::Matrix4d M = similarity(
            3.0, Eigen::AngleAxisd(2.0, Eigen::Vector3d(1, 2, 0.5).normalized()).toRotationMatrix(), {5, -2, 1});
        const KeySuggestion back =
            suggest_key(transformed(p.cut.above, M), M.inverse(), p.source_loop, p.cut.below, p.target_loop);
        CHECK(back.key.source == s.key.source);
        CHECK(back.key.target == s.key.target);
      }
  MESSAGE(cuts << " plane cuts with one matching loop each side");
  CHECK(cuts >= 20);

  // Placed turned half a turn about the cut's normal: the key follows what the user sees.
  const CutParts p = man_cut();
  const Eigen::Matrix4d half =
      similarity(1.0, Eigen::AngleAxisd(std::numbers::pi, Eigen::Vector3d(1, 0.3, 0).normalized()).toRotationMatrix(),
                 Eigen::Vector3d::Zero());
  const KeySuggestion turned = suggest_key(p.cut.above, half, p.source_loop, p.cut.below, p.target_loop);
  CHECK(p.cut.above_to_mesh[static_cast<size_t>(turned.key.source)] !=
        p.cut.below_to_mesh[static_cast<size_t>(turned.key.target)]);
}

TEST_CASE("mesh_merge: the suggested key merges the part back upright; half the loop away the turn metric flags it") {
  const CutParts p = man_cut();
  const KeySuggestion s =
      suggest_key(p.cut.above, Eigen::Matrix4d::Identity(), p.source_loop, p.cut.below, p.target_loop);
  const MergeResult upright = merge(p.cut.above, p.cut.below, {LoopPair{{s.key}}});
  const DetailPreservation d = detail_preservation(p.cut.above, upright);
  CHECK(d.turn_deg < 5);
  CHECK(seam_quality(p.cut.below, upright).folded_seam_edges == 0);

  // The key's target half the loop's vertices further on.
  const auto at = std::find(p.target_loop.begin(), p.target_loop.end(), s.key.target) - p.target_loop.begin();
  const int opposite =
      p.target_loop[static_cast<size_t>(at + static_cast<long>(p.target_loop.size()) / 2) % p.target_loop.size()];
  const MergeResult flipped = merge(p.cut.above, p.cut.below, {LoopPair{{{s.key.source, opposite}}}});
  const DetailPreservation f = detail_preservation(p.cut.above, flipped);
  MESSAGE("turn with the suggested key " << d.turn_deg << " deg, with the opposite one " << f.turn_deg << " deg");
  CHECK(f.turn_deg > 90);
}

TEST_CASE(
    "mesh_merge: suggest_keys fills every pair; the user's first key replaces the suggestion; errors name the cause") {
  const CutParts p = man_cut();
  MergeSetup setup;
  setup.source = std::make_shared<const TriMesh>(p.cut.above);
  setup.target = std::make_shared<const TriMesh>(p.cut.below);
  pair_loops(setup, 0, 0);
  const std::vector<KeySuggestion> s = suggest_keys(setup, {p.source_loop}, {p.target_loop});
  REQUIRE(s.size() == 1);
  REQUIRE(setup.pairs[0].keys.size() == 1);
  CHECK(setup.pairs[0].keys_suggested);
  CHECK(missing_input(setup, 1).empty());
  // A key the user clicks elsewhere replaces the suggestion rather than joining it.
  const KeyCorrespondence mine{p.source_loop[3], p.target_loop[p.target_loop.size() - 3]};
  add_key(setup, 0, mine, p.source_loop);
  REQUIRE(setup.pairs[0].keys.size() == 1);
  CHECK(setup.pairs[0].keys[0].source == mine.source);
  CHECK_FALSE(setup.pairs[0].keys_suggested);
  // A second one joins it.
  add_key(setup, 0, {p.source_loop[p.source_loop.size() / 2], p.target_loop[p.target_loop.size() / 2]}, p.source_loop);
  CHECK(setup.pairs[0].keys.size() == 2);

  CHECK_THROWS_WITH_AS(suggest_keys(setup, {p.source_loop}, {p.target_loop}, 1),
                       "mesh_merge::suggest_keys(): pair 1 out of range", InvalidArgument);
  CHECK_THROWS_WITH_AS(suggest_keys(setup, {}, {p.target_loop}),
                       "mesh_merge::suggest_keys(): pair 0 names loops 0 and 0, but the meshes have 0 and 1",
                       InvalidArgument);
  CHECK_THROWS_WITH_AS(suggest_key(p.cut.above, Eigen::Matrix4d::Identity(), {0, 1}, p.cut.below, p.target_loop),
                       "mesh_merge::suggest_key(): source loop has 2 vertices, expected 3 or more", InvalidArgument);
  CHECK_THROWS_WITH_AS(
      suggest_key(p.cut.above, Eigen::Matrix4d::Identity(), {0, 1, p.cut.above.num_vertices()}, p.cut.below,
                  p.target_loop),
      ("mesh_merge::suggest_key(): source loop vertex " + std::to_string(p.cut.above.num_vertices()) + " out of range")
          .c_str(),
      InvalidArgument);
  CHECK_THROWS_WITH_AS(suggest_key(p.cut.above, Eigen::Matrix4d::Zero(), p.source_loop, p.cut.below, p.target_loop),
                       "mesh_merge::suggest_key(): source loop has no length", InvalidArgument);
}
