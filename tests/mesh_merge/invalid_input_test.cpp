#include <doctest/doctest.h>

#include "merge_fixtures.h"

using namespace lapis;
using namespace lapis::mesh_merge;

namespace {

std::string merge_error(const TriMesh& src, const TriMesh& tgt, const std::vector<LoopPair>& pairs,
                        const MergeOptions& o = {}) {
  try {
    merge(src, tgt, pairs, o);
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "no error";
}

bool starts_with(const std::string& s, const std::string& p) { return s.rfind(p, 0) == 0; }

}  // namespace

TEST_CASE("mesh_merge: invalid inputs throw errors naming the cause") {
  const TriMesh src = test::dome(2), tgt = test::body(24, 8);
  const std::vector<LoopPair> good = test::dome_on_body(src, tgt);
  const std::string check = "mesh_merge::check_merge_input(): ";

  SUBCASE("mismatched pair counts") {
    std::string e = merge_error(src, tgt, {});
    CHECK(starts_with(e, check));
    CHECK(e.find("0 loop pairs for a source with 1 boundary loops") != std::string::npos);
    std::vector<LoopPair> two = {good[0], good[0]};
    CHECK(merge_error(src, tgt, two).find("2 loop pairs for a source with 1") != std::string::npos);
  }
  SUBCASE("a pair without keys") {
    CHECK(merge_error(src, tgt, {LoopPair{}}) == check + "pair 0 has no key correspondence, expected at least one");
  }
  SUBCASE("correspondence vertex not on the loop") {
    int interior = 0;
    const geometry::Connectivity c(src);
    while (c.is_boundary_vertex(interior)) ++interior;
    std::vector<LoopPair> p = good;
    p[0].keys[0].source = interior;
    CHECK(merge_error(src, tgt, p) ==
          check + "pair 0 key 0: source vertex " + std::to_string(interior) + " is not on a boundary loop");
    // Second key on the target's other loop.
    p = good;
    const geometry::Connectivity ct(tgt);
    const auto& other = ct.boundary_loops()[std::find(ct.boundary_loops()[0].begin(), ct.boundary_loops()[0].end(),
                                                      good[0].keys[0].target) == ct.boundary_loops()[0].end()
                                                ? 0
                                                : 1];
    const auto& sl = c.boundary_loops()[0];
    p[0].keys.push_back({sl[sl.size() / 2], other[0]});
    CHECK(merge_error(src, tgt, p) == check + "pair 0 key 1: target vertex " + std::to_string(other[0]) +
                                          " is not on the loop of the pair's first key");
    p = good;
    p[0].keys[0].target = tgt.num_vertices();
    CHECK(merge_error(src, tgt, p) ==
          check + "pair 0 key 0: target vertex " + std::to_string(tgt.num_vertices()) + " out of range");
  }
  SUBCASE("closed source") {
    const TriMesh closed = geometry::make_icosphere(2);
    CHECK(merge_error(closed, tgt, good) ==
          check + "the source is closed (no boundary loop), expected an open merging boundary");
  }
  SUBCASE("non-manifold boundary") {
    // A second dome sharing one boundary vertex with the first: a bowtie on the boundary.
    TriMesh two = src;
    const int n = src.num_vertices();
    const int shared = good[0].keys[0].source;
    two.V.conservativeResize(2 * n, 3);
    two.V.bottomRows(n) = src.V;
    two.V.bottomRows(n).col(0).array() += 5;
    two.F.conservativeResize(2 * src.num_faces(), 3);
    two.F.bottomRows(src.num_faces()) = src.F.array() + n;
    for (int f = src.num_faces(); f < two.num_faces(); ++f)
      for (int k = 0; k < 3; ++k)
        if (two.F(f, k) == shared + n) two.F(f, k) = shared;
    const std::string e = merge_error(two, tgt, good);
    CHECK(starts_with(e, check + "the source is not manifold"));
    CHECK(e.find("non-manifold vert") != std::string::npos);
  }
  SUBCASE("a face naming a vertex twice") {
    TriMesh bad = src;
    bad.F(3, 2) = bad.F(3, 0);
    CHECK(merge_error(bad, tgt, good) == check + "the source's face 3 (" + std::to_string(bad.F(3, 0)) + ", " +
                                             std::to_string(bad.F(3, 1)) + ", " + std::to_string(bad.F(3, 0)) +
                                             ") names a vertex twice");
  }
  SUBCASE("keys in opposite cyclic orders") {
    const geometry::Connectivity cs(src), ct(tgt);
    const auto& sl = cs.boundary_loops()[0];
    std::vector<LoopPair> p = good;
    // Source keys advance forward; the matching target keys must go backward round the loop.
    int tl = 0;
    if (std::find(ct.boundary_loops()[0].begin(), ct.boundary_loops()[0].end(), good[0].keys[0].target) ==
        ct.boundary_loops()[0].end())
      tl = 1;
    const auto& tloop = ct.boundary_loops()[tl];
    const size_t s0 = std::find(sl.begin(), sl.end(), good[0].keys[0].source) - sl.begin();
    const size_t t0 = std::find(tloop.begin(), tloop.end(), good[0].keys[0].target) - tloop.begin();
    p[0].keys.push_back({sl[(s0 + sl.size() / 3) % sl.size()], tloop[(t0 + tloop.size() / 3) % tloop.size()]});
    p[0].keys.push_back({sl[(s0 + 2 * sl.size() / 3) % sl.size()], tloop[(t0 + 2 * tloop.size() / 3) % tloop.size()]});
    CHECK(merge_error(src, tgt, p).find("not in the same cyclic order") != std::string::npos);
  }
  SUBCASE("options out of range") {
    MergeOptions o;
    o.smooth_lambda = 2;
    CHECK(merge_error(src, tgt, good, o) == "mesh_merge::merge(): smooth_lambda must be in (0, 1]");
    o = {};
    o.mode = MergeMode::Dependent;
    o.handles = {good[0].keys[0].source};
    CHECK(merge_error(src, tgt, good, o) == "mesh_merge::merge(): handle vertex " +
                                                std::to_string(good[0].keys[0].source) +
                                                " lies on the merging boundary");
  }
}
