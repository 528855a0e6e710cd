// The seam's clean-up after zipping: folded strip edges unfolded by moving only what may move.
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
