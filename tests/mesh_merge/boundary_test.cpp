#include <doctest/doctest.h>

#include "lapis/geometry/procedural.h"
#include "lapis/mesh_merge/constraints.h"
#include "lapis/mesh_merge/refine.h"
#include "lapis/mesh_merge/transition.h"
#include "merge_fixtures.h"

using namespace lapis;
using namespace lapis::mesh_merge;

namespace {

// A noisy sphere cut in two along z = 0.1: both parts share the cut loop's vertices.
struct SelfCut {
  PlaneCut cut;
  std::vector<LoopPair> pairs;
  SelfCut(std::vector<int> key_fractions = {0}) {
    TriMesh s = geometry::make_icosphere(3);
    test::jitter(s, 0.01, 3);
    cut = cut_by_plane(s, {0, 0, 0.1}, {0, 0, 1});
    const geometry::Connectivity ca(cut.above);
    std::vector<int> mesh_to_below(static_cast<size_t>(s.num_vertices()), -1);
    for (size_t v = 0; v < cut.below_to_mesh.size(); ++v) mesh_to_below[cut.below_to_mesh[v]] = static_cast<int>(v);
    const auto& loop = ca.boundary_loops().at(0);
    LoopPair p;
    for (int f : key_fractions) {
      const int a = loop[static_cast<size_t>(f) * loop.size() / 100];
      p.keys.push_back({a, mesh_to_below[cut.above_to_mesh[a]]});
    }
    pairs = {p};
  }
};

}  // namespace

TEST_CASE("mesh_merge: arc-length correspondence maps a shared cut loop onto itself") {
  for (const auto& keys : {std::vector<int>{0}, std::vector<int>{0, 30, 70}}) {
    SelfCut sc(keys);
    const geometry::Connectivity ca(sc.cut.above), cb(sc.cut.below);
    const auto corr = correspond_boundaries(sc.cut.above, ca, sc.cut.below, cb, sc.pairs);
    REQUIRE(corr.size() == 1);
    REQUIRE(corr[0].source_loop.size() == corr[0].target_loop.size());
    for (size_t i = 0; i < corr[0].source_loop.size(); ++i)
      CHECK((corr[0].target_points.row(i) - sc.cut.above.V.row(corr[0].source_loop[i])).norm() < 1e-12);
    const auto cons = boundary_constraints(sc.cut.above, sc.cut.below, corr, false);
    for (const auto& k : cons) {
      CHECK(k.scale == doctest::Approx(1.0).epsilon(1e-9));
      // One-sided normals differ a little across the cut; the frames stay close (< ~20°).
      CHECK((k.rotation - Eigen::Matrix3d::Identity()).norm() < 0.5);
    }
  }
}

TEST_CASE("mesh_merge: key vertices land exactly on their targets and arcs scale by length") {
  const TriMesh src = test::dome(), tgt = test::body();
  const geometry::Connectivity cs(src), ct(tgt);
  const auto& sloop = cs.boundary_loops()[0];
  std::vector<LoopPair> pairs = test::dome_on_body(src, tgt);
  // A second key half-way round both loops (by index; the target loop runs backward).
  const int s0 = static_cast<int>(std::find(sloop.begin(), sloop.end(), pairs[0].keys[0].source) - sloop.begin());
  const int s1 = sloop[(static_cast<size_t>(s0) + sloop.size() / 2) % sloop.size()];
  int t1 = -1;
  for (const auto& l : ct.boundary_loops()) {
    const auto it = std::find(l.begin(), l.end(), pairs[0].keys[0].target);
    if (it != l.end()) t1 = l[(static_cast<size_t>(it - l.begin()) + l.size() - l.size() / 2) % l.size()];
  }
  REQUIRE(t1 >= 0);
  pairs[0].keys.push_back({s1, t1});
  const auto corr = correspond_boundaries(src, cs, tgt, ct, pairs);
  const auto& c = corr[0];
  CHECK((c.target_points.row(0) - tgt.V.row(pairs[0].keys[0].target)).norm() == 0);
  const auto i1 = std::find(c.source_loop.begin(), c.source_loop.end(), s1) - c.source_loop.begin();
  CHECK((c.target_points.row(i1) - tgt.V.row(t1)).norm() == 0);
  // Parameters advance monotonically along the target loop.
  for (size_t i = 1; i < c.source_loop.size(); ++i)
    CHECK(c.target_edge[i] + c.target_t[i] >= c.target_edge[i - 1] + c.target_t[i - 1]);
}

TEST_CASE("mesh_merge: boundary refinement splits boundary edges and keeps indices") {
  TriMesh m = test::dome(2);
  const TriMesh before = m;
  const geometry::Connectivity c0(m);
  const size_t b0 = c0.boundary_loops()[0].size();
  const int added = split_boundary_edges(m);
  CHECK(added > 0);
  CHECK(m.V.topRows(before.num_vertices()) == before.V);
  const geometry::Connectivity c1(m);
  CHECK(c1.boundary_loops().size() == 1);
  CHECK(c1.boundary_loops()[0].size() == b0 + static_cast<size_t>(added));
  CHECK(geometry::validate(m).ok());
  TriMesh r = test::dome(2);
  CHECK(refine_short_boundary(r, 100.0, 2) == 2);
  TriMesh q = test::dome(2);
  CHECK(refine_short_boundary(q, 0.0, 2) == 0);
}

TEST_CASE("mesh_merge: a loop's ring is made an annulus where the mesh reaches back to the loop") {
  // A 2×1 strip of quads: every vertex is on the loop, and the diagonals join loop vertices
  // across the mesh, so no band next to the loop is an annulus.
  TriMesh m = geometry::make_plane_grid(2, 1);
  const TriMesh before = m;
  std::vector<int> loop = geometry::Connectivity(m).boundary_loops().at(0);
  CHECK_FALSE(band_is_annulus(m, geometry::Connectivity(m), loop, 0.01, "target"));
  const int added = separate_loop_neighbourhoods(m, {loop});
  CHECK(added > 0);
  CHECK(m.V.topRows(before.num_vertices()) == before.V);  // indices kept
  const geometry::Connectivity conn(m);
  REQUIRE(conn.boundary_loops().size() == 1);
  CHECK(conn.boundary_loops()[0].size() == loop.size());  // the loop itself unchanged
  CHECK(geometry::validate(m).ok());
  CHECK(band_is_annulus(m, conn, loop, 0.01, "target"));
  // Nothing to separate: the mesh is left alone.
  TriMesh dome = test::dome(2);
  const TriMesh dome_before = dome;
  CHECK(separate_loop_neighbourhoods(dome, geometry::Connectivity(dome).boundary_loops()) == 0);
  CHECK(dome.F == dome_before.F);
}
