// What the merge app hands the module besides meshes: parts cut along a painted region's
// border, pairs and handles files (the format `lapis merge` reads), seam smoothing changed
// on a precomputed Merger.
#include <doctest/doctest.h>

#include <fstream>

#include "lapis/mesh_merge/merge_setup.h"
#include "lapis/mesh_merge/metrics.h"
#include "lapis/mesh_merge/pairs_file.h"
#include "merge_fixtures.h"

using namespace lapis;
using namespace lapis::mesh_merge;

namespace {

std::filesystem::path scratch(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("lapis_merge_inputs_" + std::to_string(::getpid()) + "_" + name);
}

}  // namespace

TEST_CASE("mesh_merge: cut_by_region splits a closed mesh into two parts with one boundary loop each") {
  const TriMesh sphere = geometry::make_icosphere(3, 1.0);
  std::vector<int> cap;  // a painted cap: the vertices above z = 0.5
  for (int v = 0; v < sphere.num_vertices(); ++v)
    if (sphere.V(v, 2) > 0.5) cap.push_back(v);
  const RegionCut cut = cut_by_region(sphere, cap);
  CHECK(cut.inside.num_faces() + cut.outside.num_faces() == sphere.num_faces());
  const geometry::Connectivity in(cut.inside), out(cut.outside);
  REQUIRE(in.boundary_loops().size() == 1);
  REQUIRE(out.boundary_loops().size() == 1);
  // The two rims are the same cycle of original vertices.
  std::vector<int> a, b;
  for (int v : in.boundary_loops()[0]) a.push_back(cut.inside_to_mesh[v]);
  for (int v : out.boundary_loops()[0]) b.push_back(cut.outside_to_mesh[v]);
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  CHECK(a == b);
  for (int v = 0; v < cut.inside.num_vertices(); ++v) {
    CHECK(cut.inside.V.row(v) == sphere.V.row(cut.inside_to_mesh[v]));
    CHECK(sphere.V(cut.inside_to_mesh[v], 2) > 0.5);
  }
}

TEST_CASE("mesh_merge: cut_by_region closes a region that touches itself at a vertex") {
  // Around a valence-6 vertex v, painting v, r0, r1, r3, r4 makes faces (v, r0, r1) and
  // (v, r3, r4) inside, touching only at v: cut as they are, both parts would pinch there.
  const TriMesh sphere = geometry::make_icosphere(3, 1.0);
  const geometry::Connectivity conn(sphere);
  int v = 0;
  while (conn.degree(v) != 6) ++v;
  const std::vector<int> ring = conn.one_ring_ordered(v);
  const RegionCut cut = cut_by_region(sphere, {v, ring[0], ring[1], ring[3], ring[4]});
  CHECK(geometry::validate(cut.inside).non_manifold_vertices.empty());
  CHECK(geometry::validate(cut.outside).non_manifold_vertices.empty());
  CHECK(cut.inside.num_faces() == 6);  // the whole fan around v
  CHECK(geometry::Connectivity(cut.outside).boundary_loops().size() == 1);
}

TEST_CASE("mesh_merge: cut_by_region fills unpainted islands inside the region") {
  // A cap painted with one vertex left out: without filling, the cap would have two loops.
  const TriMesh sphere = geometry::make_icosphere(3, 1.0);
  std::vector<int> cap;
  int top = 0;
  for (int v = 0; v < sphere.num_vertices(); ++v) {
    if (sphere.V(v, 2) > sphere.V(top, 2)) top = v;
  }
  for (int v = 0; v < sphere.num_vertices(); ++v)
    if (sphere.V(v, 2) > 0.3 && v != top) cap.push_back(v);
  const RegionCut cut = cut_by_region(sphere, cap);
  CHECK(geometry::Connectivity(cut.inside).boundary_loops().size() == 1);
  CHECK(cut.inside.num_faces() + cut.outside.num_faces() == sphere.num_faces());
}

TEST_CASE("mesh_merge: cut_by_region names what is wrong with the region") {
  const TriMesh sphere = geometry::make_icosphere(2, 1.0);
  CHECK_THROWS_WITH_AS(
      cut_by_region(sphere, {0}),
      "mesh_merge::cut_by_region(): no face has all three corners in the region, expected a painted area",
      InvalidArgument);
  std::vector<int> all(static_cast<size_t>(sphere.num_vertices()));
  for (int v = 0; v < sphere.num_vertices(); ++v) all[static_cast<size_t>(v)] = v;
  CHECK_THROWS_WITH_AS(cut_by_region(sphere, all),
                       "mesh_merge::cut_by_region(): the region covers the whole mesh, expected a part of it",
                       InvalidArgument);
  CHECK_THROWS_WITH_AS(cut_by_region(sphere, {-1}), "mesh_merge::cut_by_region(): region vertex -1 out of range",
                       InvalidArgument);
}

TEST_CASE("mesh_merge: pairs and handles files round-trip and reject malformed content") {
  const std::vector<LoopPair> pairs{LoopPair{{{3, 30}, {7, 12}}}, LoopPair{{{40, 2}}}};
  const auto path = scratch("pairs.json");
  write_pairs_file(path, pairs);
  const std::vector<LoopPair> back = read_pairs_file(path);
  REQUIRE(back.size() == 2);
  REQUIRE(back[0].keys.size() == 2);
  CHECK(back[0].keys[1].source == 7);
  CHECK(back[0].keys[1].target == 12);
  CHECK(back[1].keys[0].source == 40);

  const auto hpath = scratch("handles.json");
  write_handles_file(hpath, {5, 6, 9});
  CHECK(read_handles_file(hpath) == std::vector<int>{5, 6, 9});

  {
    std::ofstream bad(path);
    bad << R"({"pairs": [{"keys": [{"source": 1.5, "target": 2}]}]})";
  }
  CHECK_THROWS_WITH_AS(read_pairs_file(path),
                       ("mesh_merge::read_pairs_file(): " + path.string() +
                        ": pairs[0].keys[0].source: expected an integer in [0, 2147483647], found '1.5'")
                           .c_str(),
                       InvalidArgument);
  // Integers beyond int are refused, not wrapped (4294967471 would be vertex 175).
  std::ofstream(path) << R"({"pairs": [{"keys": [{"source": 4294967471, "target": 2}]}]})";
  CHECK_THROWS_WITH_AS(
      read_pairs_file(path),
      doctest::Contains("pairs[0].keys[0].source: expected an integer in [0, 2147483647], found 4294967471"),
      InvalidArgument);
  std::ofstream(hpath) << R"({"handles": [3, -4]})";
  CHECK_THROWS_WITH_AS(read_handles_file(hpath),
                       doctest::Contains("handles[1]: expected an integer in [0, 2147483647], found -4"),
                       InvalidArgument);
  {
    std::ofstream bad(path);
    bad << "{\"pairs\": ";
  }
  CHECK_THROWS_AS(read_pairs_file(path), IoError);
  CHECK_THROWS_AS(read_pairs_file(scratch("missing.json")), IoError);
  std::filesystem::remove(path);
  std::filesystem::remove(hpath);
}

TEST_CASE("mesh_merge: Merger::set_smoothing re-merges like a Merger built with those options") {
  const TriMesh src = test::dome(), tgt = test::body();
  const std::vector<LoopPair> pairs = test::dome_on_body(src, tgt);
  Merger merger(src);
  const MergeResult smooth3 = merger.merge(tgt, pairs);
  merger.set_smoothing(0, 1, 0.5);
  const MergeResult unsmoothed = merger.merge(tgt, pairs);
  MergeOptions o;
  o.smooth_iterations = 0;
  const MergeResult fresh = merge(src, tgt, pairs, o);
  // Equal to rounding: the re-merge's polar decompositions start from the first merge's
  // rotations (mesh_deform warm-starts them), a fresh Merger's from the identity.
  const double diagonal = (fresh.mesh.V.colwise().maxCoeff() - fresh.mesh.V.colwise().minCoeff()).norm();
  CHECK((unsmoothed.mesh.V - fresh.mesh.V).cwiseAbs().maxCoeff() <= 1e-12 * diagonal);
  CHECK((unsmoothed.mesh.V - smooth3.mesh.V).cwiseAbs().maxCoeff() > 1e-6 * diagonal);  // smoothing really changed
  CHECK(unsmoothed.smoothed.empty());
  CHECK_THROWS_WITH_AS(merger.set_smoothing(-1, 1, 0.5),
                       "mesh_merge::merge(): smooth_iterations and smooth_rings must be >= 0", InvalidArgument);
}

TEST_CASE("mesh_merge: MergeSetup edits keep one pair per loop and keys in loop order") {
  MergeSetup s;
  s.source = std::make_shared<const TriMesh>(test::dome());
  s.target = std::make_shared<const TriMesh>(test::body());
  const geometry::Connectivity sc(*s.source), tc(*s.target);
  CHECK(missing_input(s, 1) == "pair every source boundary loop with a target loop (0 of 1 paired)");
  CHECK(pair_loops(s, 0, 1) == 0);
  CHECK(pair_loops(s, 0, 0) == 0);  // re-pairing the source loop replaces the pair
  REQUIRE(s.pairs.size() == 1);
  CHECK(s.pairs[0].target_loop == 0);
  CHECK(missing_input(s, 1) == "pair 1 needs a key correspondence");
  const auto& loop = sc.boundary_loops()[0];
  const auto& tloop = tc.boundary_loops()[0];
  add_key(s, 0, {loop[10], tloop[3]}, loop);
  add_key(s, 0, {loop[2], tloop[9]}, loop);
  add_key(s, 0, {loop[10], tloop[5]}, loop);  // same source vertex: replaced
  REQUIRE(s.pairs[0].keys.size() == 2);
  CHECK(s.pairs[0].keys[0].source == loop[2]);
  CHECK(s.pairs[0].keys[1].target == tloop[5]);
  CHECK(missing_input(s, 1).empty());
  CHECK_THROWS_WITH_AS(add_key(s, 0, {0, tloop[0]}, loop),
                       "mesh_merge::add_key(): source vertex 0 is not on the pair's source loop", InvalidArgument);
  CHECK_THROWS_AS(add_key(s, 3, {loop[0], tloop[0]}, loop), InvalidArgument);
  CHECK(loop_pairs(s).size() == 1);

  toggle_handle(s, 12);
  toggle_handle(s, 13);
  toggle_handle(s, 12);
  CHECK(s.options.handles == std::vector<int>{13});

  // Placement: identity leaves the mesh bit for bit; a translation moves every vertex.
  CHECK(placed_source(s).V == s.source->V);
  s.placement(2, 3) = 1.5;
  CHECK((placed_source(s).V.col(2).array() - s.source->V.col(2).array() - 1.5).abs().maxCoeff() < 1e-15);
}

// A closed mesh gives no loop to size and place the source by: it goes beside the target at half
// the target's size (the merge app opens a mesh so; it once arrived unscaled on top).
TEST_CASE("mesh_merge: suggest_placement sets a closed source beside the target at half its size") {
  geometry::TriMesh source = geometry::make_icosphere(2, 30.0), target = geometry::make_torus(24, 12, 1.0, 0.4);
  source.V.rowwise() += Eigen::RowVector3d(5, -7, 2);
  const Eigen::Matrix4d T = suggest_placement(source, target);
  geometry::TriMesh placed = source;
  placed.V = (source.V * T.topLeftCorner<3, 3>().transpose()).rowwise() + T.topRightCorner<3, 1>().transpose();
  auto diagonal = [](const geometry::TriMesh& m) {
    return (m.V.colwise().maxCoeff() - m.V.colwise().minCoeff()).norm();
  };
  auto centre = [](const geometry::TriMesh& m) {
    return Eigen::RowVector3d(0.5 * (m.V.colwise().maxCoeff() + m.V.colwise().minCoeff()));
  };
  CHECK(diagonal(placed) == doctest::Approx(0.5 * diagonal(target)));
  CHECK(placed.V.col(0).minCoeff() == doctest::Approx(target.V.col(0).maxCoeff() + 0.05 * diagonal(target)));
  CHECK((centre(placed).tail<2>() - centre(target).tail<2>()).norm() < 1e-12);
  // A similarity: the source keeps its shape and orientation.
  const Eigen::Matrix3d L = T.topLeftCorner<3, 3>();
  CHECK((L - L(0, 0) * Eigen::Matrix3d::Identity()).norm() < 1e-15);
  CHECK(suggest_placement(geometry::TriMesh{}, target).isIdentity());
}
