#include <doctest/doctest.h>

#include <Eigen/Geometry>

#include "lapis/geometry/polar.h"
#include "lapis/mesh_merge/metrics.h"
#include "merge_fixtures.h"

using namespace lapis;
using namespace lapis::mesh_merge;

TEST_CASE("mesh_merge: dihedral deviation is zero on a plane and the cylinder's turn angle on a cylinder") {
  for (double a : dihedral_deviation_deg(geometry::make_plane_grid(6, 5)))
    CHECK(a == doctest::Approx(0).epsilon(1e-12));
  const auto cyl = dihedral_deviation_deg(geometry::make_cylinder(36, 4));
  CHECK(*std::max_element(cyl.begin(), cyl.end()) == doctest::Approx(10.0).epsilon(1e-9));
}

TEST_CASE("mesh_merge: seam metrics see a hole, a moved target vertex and distorted details") {
  const TriMesh src = test::dome(), tgt = test::body();
  MergeResult r = merge(src, tgt, test::dome_on_body(src, tgt));
  const SeamQuality good = seam_quality(tgt, r);
  REQUIRE(good.valid());
  CHECK(good.seam_dihedral_mean_deg > 0);
  CHECK(good.target_dihedral_p95_deg > 0);
  const DetailPreservation d0 = detail_preservation(src, r);
  CHECK(d0.laplacian_residual < 0.5);

  MergeResult holed = r;
  // Remove strip face f by moving the last face into its slot; keep strip_faces in range.
  const int f = holed.strip_faces.back(), last = holed.mesh.num_faces() - 1;
  holed.mesh.F.row(f) = holed.mesh.F.row(last);
  holed.mesh.F.conservativeResize(last, 3);
  holed.strip_faces.pop_back();
  for (int& s : holed.strip_faces)
    if (s == last) s = f;
  CHECK(seam_quality(tgt, holed).seam_boundary_edges >= 2);
  CHECK(!seam_quality(tgt, holed).valid());

  CHECK(good.folded_seam_edges == 0);
  MergeResult spiked = r;
  // A strip triangle turned over faces against the surface on all three of its edges, as a
  // spike or a notch of the zip does.
  const int flipped = r.strip_faces[r.strip_faces.size() / 2];
  std::swap(spiked.mesh.F(flipped, 1), spiked.mesh.F(flipped, 2));
  const SeamQuality folded = seam_quality(tgt, spiked);
  CHECK(folded.folded_seam_edges > 0);
  CHECK(folded.seam_dihedral_max_deg > geometry::kFoldedDihedralDeg);
  CHECK(!folded.valid());

  MergeResult moved = r;
  int far = 0;
  while (moved.target_map[far] < 0 || std::binary_search(r.smoothed.begin(), r.smoothed.end(), moved.target_map[far]))
    ++far;
  moved.mesh.V(moved.target_map[far], 0) += 0.01;
  CHECK(seam_quality(tgt, moved).max_target_displacement > 0);

  MergeResult bumped = r;
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  for (int v = 0; v < src.num_vertices(); ++v)
    for (int a = 0; a < 3; ++a) bumped.mesh.V(bumped.source_map[v], a) += u(rng);
  const DetailPreservation d1 = detail_preservation(src, bumped);
  CHECK(d1.laplacian_residual > 2 * d0.laplacian_residual);
  CHECK(d1.mean_distance > d0.mean_distance);
}

TEST_CASE("mesh_merge: feature distortion is zero for a similar copy and measures a moved vertex") {
  const TriMesh src = test::dome();
  geometry::Similarity3 G;
  G.s = 2.5, G.R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  G.t = Eigen::Vector3d(4, -1, 2);
  MergeResult r;
  r.mesh = src;
  for (int v = 0; v < src.num_vertices(); ++v) r.mesh.V.row(v) = G(src.V.row(v).transpose()).transpose();
  r.source_map.resize(static_cast<size_t>(src.num_vertices()));
  std::vector<int> part;
  for (int v = 0; v < src.num_vertices(); ++v) {
    r.source_map[v] = v;
    if (src.V(v, 2) > 0.5) part.push_back(v);
  }
  REQUIRE(part.size() > 20);
  CHECK(feature_distortion(src, r, part) < 1e-12);
  // One vertex pushed off the similar copy by a tenth of the part's diagonal: the fit spreads
  // some of it over the others, so the largest distance stays between half and all of it.
  const double diagonal = bbox_diagonal(r.mesh.V(part, Eigen::all));
  r.mesh.V.row(part[part.size() / 2]) += Eigen::RowVector3d(0, 0, 0.1 * diagonal);
  const double moved = feature_distortion(src, r, part);
  CHECK(moved > 0.05);
  CHECK(moved < 0.11);
  CHECK_THROWS_WITH_AS(feature_distortion(src, r, {part[0], part[1]}),
                       doctest::Contains("mesh_merge::feature_distortion(): a part needs at least 3 vertices"),
                       InvalidArgument);
  r.source_map[part[3]] = -1;
  CHECK_THROWS_WITH_AS(
      feature_distortion(src, r, part),
      doctest::Contains(("vertex " + std::to_string(part[3]) + " is not a merged source vertex").c_str()),
      InvalidArgument);
}
