#include <doctest/doctest.h>

#include "lapis/mesh_merge/metrics.h"
#include "merge_fixtures.h"

using namespace lapis;
using namespace lapis::mesh_merge;

namespace {

int boundary_loop_count(const TriMesh& m) {
  return static_cast<int>(geometry::Connectivity(m).boundary_loops().size());
}

}  // namespace

TEST_CASE("mesh_merge: one loop pair gives a watertight manifold seam") {
  const TriMesh src = test::dome(), tgt = test::body();
  const MergeResult r = merge(src, tgt, test::dome_on_body(src, tgt));
  test::require_watertight(tgt, r);
  // The body's bottom loop stays open; the top one is closed by the dome.
  CHECK(boundary_loop_count(r.mesh) == 1);
  CHECK(geometry::genus(r.mesh) == 0);
  // The source boundary lies on the target boundary before zipping.
  for (int v : r.source_boundary) CHECK(std::abs(r.source_deformed(v, 2) - 2.0) < 0.01);
}

TEST_CASE("mesh_merge: several loop pairs at once (a tube between two column halves)") {
  const TriMesh src = test::tube(), tgt = test::split_column();
  const MergeResult r = merge(src, tgt, test::tube_in_column(src, tgt));
  test::require_watertight(tgt, r);
  CHECK(boundary_loop_count(r.mesh) == 2);  // the column's two outer ends
  CHECK(geometry::connected_components(r.mesh).count == 1);
  // The tube widened from radius 0.5 to the column's 1 at both ends.
  for (int v : r.source_boundary)
    CHECK(r.source_deformed.row(v).head<2>().norm() == doctest::Approx(1.0).epsilon(0.02));
}

TEST_CASE("mesh_merge: target vertices away from the seam do not move") {
  const TriMesh src = test::dome(), tgt = test::body();
  for (int smooth : {0, 3}) {
    MergeOptions o;
    o.smooth_iterations = smooth;
    o.smooth_rings = 2;
    const MergeResult r = merge(src, tgt, test::dome_on_body(src, tgt), o);
    std::vector<char> band(static_cast<size_t>(r.mesh.num_vertices()), 0);
    for (int v : r.smoothed) band[v] = 1;
    int kept = 0;
    for (int v = 0; v < tgt.num_vertices(); ++v) {
      const int m = r.target_map[v];
      if (m < 0 || band[m]) continue;
      ++kept;
      CHECK(r.mesh.V.row(m) == tgt.V.row(v));
    }
    CHECK(kept > tgt.num_vertices() * 8 / 10);
    CHECK(seam_quality(tgt, r).max_target_displacement == 0.0);
    if (smooth == 0) CHECK(r.smoothed.empty());
  }
}

TEST_CASE("mesh_merge: merging a part back onto the rest of its mesh returns the original geometry") {
  TriMesh s = geometry::make_icosphere(4);
  test::jitter(s, 0.003, 21);
  const PlaneCut cut = cut_by_plane(s, {0, 0, 0.3}, {0, 0, 1});
  std::vector<int> mesh_to_below(static_cast<size_t>(s.num_vertices()), -1);
  for (size_t v = 0; v < cut.below_to_mesh.size(); ++v) mesh_to_below[cut.below_to_mesh[v]] = static_cast<int>(v);
  const int key = geometry::Connectivity(cut.above).boundary_loops()[0][0];
  const std::vector<LoopPair> pairs{LoopPair{{{key, mesh_to_below[cut.above_to_mesh[key]]}}}};
  MergeOptions o;
  o.refine_levels = 0;  // the shared loop must stay vertex for vertex
  const MergeResult r = merge(cut.above, cut.below, pairs, o);
  test::require_watertight(cut.below, r);
  // Source vertices off the smoothed band: back where they were on the sphere, up to the
  // one-sided boundary normals (frames differ slightly across the cut).
  std::vector<char> band(static_cast<size_t>(r.mesh.num_vertices()), 0);
  for (int v : r.smoothed) band[v] = 1;
  double worst = 0;
  for (int v = 0; v < cut.above.num_vertices(); ++v)
    if (!band[r.source_map[v]]) worst = std::max(worst, (r.mesh.V.row(r.source_map[v]) - cut.above.V.row(v)).norm());
  MESSAGE("self-merge max source deviation / diameter: " << worst / 2.0);
  CHECK(worst < 2.0 * 5e-3);
  const DetailPreservation d = detail_preservation(cut.above, r);
  CHECK(d.max_distance < 5e-3);
  // Without smoothing the solve itself is measured: the boundary returns exactly.
  o.smooth_iterations = 0;
  const MergeResult raw = merge(cut.above, cut.below, pairs, o);
  for (int v : raw.source_boundary) CHECK((raw.source_deformed.row(v) - cut.above.V.row(v)).norm() < 1e-12);
}

TEST_CASE("mesh_merge: configuration-dependent merging keeps the handles and the far source fixed") {
  TriMesh src = test::dome();
  // The user's placement: on top of the body, slightly too small.
  src.V *= 0.9;
  src.V.col(2).array() += 1.85;
  const TriMesh tgt = test::body();
  // Handle: the dome's apex region.
  std::vector<int> handles;
  for (int v = 0; v < src.num_vertices(); ++v)
    if (src.V(v, 2) > 2.6) handles.push_back(v);
  REQUIRE(!handles.empty());
  MergeOptions o;
  o.mode = MergeMode::Dependent;
  o.handles = handles;
  o.roi_width = 0.5;
  const MergeResult r = merge(src, tgt, test::dome_on_body(src, tgt), o);
  test::require_watertight(tgt, r);
  CHECK(r.refine_levels == 0);
  CHECK(r.roi_vertices < src.num_vertices());
  for (int h : handles) CHECK(r.mesh.V.row(r.source_map[h]) == src.V.row(h));
  // Boundary on the target boundary, frames kept: the dome still points up.
  for (int v : r.source_boundary) CHECK(std::abs(r.source_deformed(v, 2) - 2.0) < 0.01);
}

TEST_CASE("mesh_merge: a short boundary is refined first (§2.5) and still merges watertight") {
  const TriMesh src = test::dome(), tgt = test::body();
  MergeOptions o;
  o.refine_ratio = 10;  // force: the dome's ~45 boundary vertices are below 10 sqrt(#V)
  const MergeResult r = merge(src, tgt, test::dome_on_body(src, tgt), o);
  CHECK(r.refine_levels == 2);
  CHECK(r.source_rest.num_vertices() > src.num_vertices());
  CHECK(r.source_boundary.size() > 3 * geometry::Connectivity(src).boundary_loops()[0].size());
  CHECK(r.source_map.size() == static_cast<size_t>(src.num_vertices()));
  test::require_watertight(tgt, r);
}

TEST_CASE("mesh_merge: a source of genus one (a torus with a hole) merges onto the body") {
  TriMesh torus = geometry::make_torus(40, 20, 1.0, 0.4);
  test::jitter(torus, 0.002, 4);
  std::vector<int> hole;
  for (int f = 0; f < torus.num_faces(); ++f) {
    const Eigen::RowVector3d c =
        (torus.V.row(torus.F(f, 0)) + torus.V.row(torus.F(f, 1)) + torus.V.row(torus.F(f, 2))) / 3;
    if ((c - Eigen::RowVector3d(1.4, 0, 0)).norm() < 0.3) hole.push_back(f);  // a disc on the outer equator
  }
  const TriMesh src = geometry::remove_faces(torus, hole);
  REQUIRE(geometry::Connectivity(src).boundary_loops().size() == 1);
  const TriMesh tgt = test::body();
  const geometry::Connectivity cs(src);
  const auto& loop = cs.boundary_loops()[0];
  const int key = *std::max_element(loop.begin(), loop.end(), [&](int a, int b) { return src.V(a, 2) < src.V(b, 2); });
  const MergeResult r = merge(src, tgt, {LoopPair{{{key, test::loop_vertex_max_x(tgt, 2.0)}}}});
  test::require_watertight(tgt, r);
  CHECK(geometry::genus(r.mesh) == 1);
}

TEST_CASE("mesh_merge: one precomputed Merger gives the one-off results for other targets and keys") {
  const TriMesh src = test::dome();
  const TriMesh body = test::body(), thin = test::body(30, 10);
  Merger merger(src);
  for (const TriMesh* tgt : {&body, &thin}) {
    std::vector<LoopPair> pairs = test::dome_on_body(src, *tgt);
    for (int shift = 0; shift < 2; ++shift) {
      if (shift) {  // another key on the same loops: the user dragged the correspondence
        const geometry::Connectivity cs(src);
        const auto& loop = cs.boundary_loops()[0];
        pairs[0].keys[0].source =
            loop[(std::find(loop.begin(), loop.end(), pairs[0].keys[0].source) - loop.begin() + 3) % loop.size()];
      }
      const MergeResult reused = merger.merge(*tgt, pairs);
      const MergeResult fresh = merge(src, *tgt, pairs);
      REQUIRE(reused.mesh.F == fresh.mesh.F);
      CHECK((reused.mesh.V - fresh.mesh.V).norm() <= 1e-12 * fresh.mesh.V.norm());
    }
  }
}

TEST_CASE("mesh_merge: a source face collapsed onto its edge merges like the intact source") {
  const TriMesh intact = test::dome(), tgt = test::body();
  TriMesh src = intact;
  // A face near the top: its first corner moved onto the opposite edge, 1e-13 of the way back
  // (cotangents ~1e13 unless dropped; the merge threw "not positive definite" before).
  int f = 0;
  while (src.V(src.F(f, 0), 2) < 0.8) ++f;
  const int v = src.F(f, 0);
  const Eigen::RowVector3d edge_middle = 0.5 * (src.V.row(src.F(f, 1)) + src.V.row(src.F(f, 2)));
  src.V.row(v) = edge_middle + 1e-13 * (src.V.row(v) - edge_middle);
  const auto pairs = test::dome_on_body(src, tgt);
  const MergeResult r = merge(src, tgt, pairs), ref = merge(intact, tgt, pairs);
  CHECK(seam_quality(tgt, r).valid());
  REQUIRE(r.mesh.V.allFinite());
  double far = 0;
  for (int u = 0; u < src.num_vertices(); ++u)
    if ((intact.V.row(u) - intact.V.row(v)).norm() > 0.5)
      far = std::max(far, (r.mesh.V.row(r.source_map[u]) - ref.mesh.V.row(ref.source_map[u])).norm());
  CAPTURE(far);
  CHECK(far < 0.03);  // 0.01: the merge reshapes the dome as a whole
}
