#include "lapis/mesh_merge/boundary.h"

#include "boundary_checked.h"

#include <algorithm>
#include <numeric>
#include <string>

namespace lapis::mesh_merge {

namespace {

constexpr const char* kCheck = "mesh_merge::check_merge_input()";

// Where each vertex sits on the boundary loops: loop index and position, -1 if interior.
struct LoopIndex {
  std::vector<int> loop, position;
  LoopIndex(const Connectivity& conn) : loop(conn.num_vertices(), -1), position(conn.num_vertices(), -1) {
    const auto& loops = conn.boundary_loops();
    for (size_t l = 0; l < loops.size(); ++l)
      for (size_t i = 0; i < loops[l].size(); ++i) {
        loop[loops[l][i]] = static_cast<int>(l);
        position[loops[l][i]] = static_cast<int>(i);
      }
  }
};

[[noreturn]] void fail(const std::string& what) { throw InvalidArgument(std::string(kCheck) + ": " + what); }

void require_manifold(const TriMesh& mesh, const char* name) {
  // A face naming one vertex twice would surface below as non-manifold vertices far from it,
  // which points nowhere near the cause. (Zero-area faces with three corners are fine: their
  // cotangents are dropped, geometry::kDegenerateTriangleHeight.)
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const int a = mesh.F(f, 0), b = mesh.F(f, 1), c = mesh.F(f, 2);
    if (a == b || b == c || c == a)
      fail(std::string(name) + "'s face " + std::to_string(f) + " (" + std::to_string(a) + ", " + std::to_string(b) +
           ", " + std::to_string(c) + ") names a vertex twice");
  }
  geometry::ValidationOptions o;
  o.check_degenerate = false;
  o.check_duplicates = false;
  o.check_orientation = false;
  const geometry::ValidationReport r = geometry::validate(mesh, o);
  if (!r.ok()) fail(std::string(name) + " is not manifold (the merging boundary needs simple loops): " + r.summary(3));
}

int mod(int a, int n) { return ((a % n) + n) % n; }

// Cumulative edge lengths along a closed loop: c[i] = length from loop[0] to loop[i], c[n] = perimeter.
std::vector<double> cumulative_length(const Vertices& V, const std::vector<int>& loop) {
  const size_t n = loop.size();
  std::vector<double> c(n + 1, 0.0);
  for (size_t i = 0; i < n; ++i) c[i + 1] = c[i] + (V.row(loop[(i + 1) % n]) - V.row(loop[i])).norm();
  return c;
}

}  // namespace

double loop_perimeter(const Vertices& V, const std::vector<int>& loop) { return cumulative_length(V, loop).back(); }

void check_merge_source(const TriMesh& source, const Connectivity& source_conn) {
  if (source_conn.boundary_loops().empty())
    fail("the source is closed (no boundary loop), expected an open merging boundary");
  require_manifold(source, "the source");
}

void check_merge_input(const TriMesh& source, const Connectivity& source_conn, const TriMesh& target,
                       const Connectivity& target_conn, const std::vector<LoopPair>& pairs) {
  check_merge_source(source, source_conn);
  check_merge_pairs(source, source_conn, target, target_conn, pairs);
}

void check_merge_pairs(const TriMesh& source, const Connectivity& source_conn, const TriMesh& target,
                       const Connectivity& target_conn, const std::vector<LoopPair>& pairs) {
  const auto& sloops = source_conn.boundary_loops();
  const auto& tloops = target_conn.boundary_loops();
  if (tloops.empty()) fail("the target is closed (no boundary loop), expected an open merging boundary");
  require_manifold(target, "the target");
  if (pairs.size() != sloops.size())
    fail(std::to_string(pairs.size()) + " loop pairs for a source with " + std::to_string(sloops.size()) +
         " boundary loops, expected one pair per source loop");
  const LoopIndex sidx(source_conn), tidx(target_conn);
  std::vector<int> used_s(sloops.size(), -1), used_t(tloops.size(), -1);
  for (size_t p = 0; p < pairs.size(); ++p) {
    const auto& keys = pairs[p].keys;
    const std::string pair = "pair " + std::to_string(p);
    if (keys.empty()) fail(pair + " has no key correspondence, expected at least one");
    int sl = -1, tl = -1;
    for (size_t k = 0; k < keys.size(); ++k) {
      const int s = keys[k].source, t = keys[k].target;
      const std::string key = pair + " key " + std::to_string(k);
      if (s < 0 || s >= source.num_vertices()) fail(key + ": source vertex " + std::to_string(s) + " out of range");
      if (t < 0 || t >= target.num_vertices()) fail(key + ": target vertex " + std::to_string(t) + " out of range");
      if (sidx.loop[s] < 0) fail(key + ": source vertex " + std::to_string(s) + " is not on a boundary loop");
      if (tidx.loop[t] < 0) fail(key + ": target vertex " + std::to_string(t) + " is not on a boundary loop");
      if (k == 0) {
        sl = sidx.loop[s];
        tl = tidx.loop[t];
      } else if (sidx.loop[s] != sl) {
        fail(key + ": source vertex " + std::to_string(s) + " is not on the loop of the pair's first key");
      } else if (tidx.loop[t] != tl) {
        fail(key + ": target vertex " + std::to_string(t) + " is not on the loop of the pair's first key");
      }
    }
    if (used_s[sl] >= 0) fail(pair + " uses the source loop of pair " + std::to_string(used_s[sl]));
    if (used_t[tl] >= 0) fail(pair + " uses the target loop of pair " + std::to_string(used_t[tl]));
    used_s[sl] = used_t[tl] = static_cast<int>(p);
    // Offsets from the first key: forward on the source, backward on the target.
    const int ns = static_cast<int>(sloops[sl].size()), nt = static_cast<int>(tloops[tl].size());
    std::vector<std::pair<int, int>> offs;
    for (const auto& kc : keys)
      offs.emplace_back(mod(sidx.position[kc.source] - sidx.position[keys[0].source], ns),
                        mod(tidx.position[keys[0].target] - tidx.position[kc.target], nt));
    std::sort(offs.begin(), offs.end());
    for (size_t k = 1; k < offs.size(); ++k) {
      if (offs[k].first == offs[k - 1].first || offs[k].second == offs[k - 1].second)
        fail(pair + " repeats a key vertex");
      if (offs[k].second < offs[k - 1].second)
        fail(pair +
             ": key vertices are not in the same cyclic order on both loops (the target loop runs "
             "against the source loop at the seam)");
    }
  }
}

std::vector<BoundaryCorrespondence> correspond_boundaries(const TriMesh& source, const Connectivity& source_conn,
                                                          const TriMesh& target, const Connectivity& target_conn,
                                                          const std::vector<LoopPair>& pairs) {
  check_merge_input(source, source_conn, target, target_conn, pairs);
  return detail::correspond_checked_boundaries(source, source_conn, target, target_conn, pairs);
}

namespace detail {

std::vector<BoundaryCorrespondence> correspond_checked_boundaries(const TriMesh& source,
                                                                  const Connectivity& source_conn,
                                                                  const TriMesh& target,
                                                                  const Connectivity& target_conn,
                                                                  const std::vector<LoopPair>& pairs) {
  const LoopIndex sidx(source_conn), tidx(target_conn);
  std::vector<BoundaryCorrespondence> out;
  for (const LoopPair& pair : pairs) {
    const int k0s = pair.keys[0].source, k0t = pair.keys[0].target;
    const auto& sl = source_conn.boundary_loops()[sidx.loop[k0s]];
    const auto& tl = target_conn.boundary_loops()[tidx.loop[k0t]];
    const int ns = static_cast<int>(sl.size()), nt = static_cast<int>(tl.size());
    BoundaryCorrespondence c;
    for (int i = 0; i < ns; ++i) c.source_loop.push_back(sl[mod(sidx.position[k0s] + i, ns)]);
    for (int j = 0; j < nt; ++j) c.target_loop.push_back(tl[mod(tidx.position[k0t] - j, nt)]);
    // Key offsets along both rotated loops, closed by the first key at the end of the cycle.
    std::vector<std::pair<int, int>> keys;
    for (const auto& kc : pair.keys)
      keys.emplace_back(mod(sidx.position[kc.source] - sidx.position[k0s], ns),
                        mod(tidx.position[k0t] - tidx.position[kc.target], nt));
    std::sort(keys.begin(), keys.end());
    keys.emplace_back(ns, nt);
    const std::vector<double> ls = cumulative_length(source.V, c.source_loop);
    const std::vector<double> lt = cumulative_length(target.V, c.target_loop);
    c.target_edge.resize(ns);
    c.target_t.resize(ns);
    c.target_points.resize(ns, 3);
    for (size_t k = 0; k + 1 < keys.size(); ++k) {
      const auto [a0, b0] = keys[k];
      const auto [a1, b1] = keys[k + 1];
      const double span_s = ls[a1] - ls[a0], span_t = lt[b1] - lt[b0];
      int j = b0;
      for (int i = a0; i < a1; ++i) {
        const double f = span_s > 0 ? (ls[i] - ls[a0]) / span_s : 0.0;
        const double at = lt[b0] + f * span_t;
        while (j + 1 < b1 && lt[j + 1] <= at) ++j;
        const double len = lt[j + 1] - lt[j];
        const double t = i == a0 || len <= 0 ? 0.0 : std::clamp((at - lt[j]) / len, 0.0, 1.0);
        c.target_edge[i] = j % nt;
        c.target_t[i] = t;
        c.target_points.row(i) =
            (1 - t) * target.V.row(c.target_loop[j % nt]) + t * target.V.row(c.target_loop[(j + 1) % nt]);
      }
    }
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace detail
}  // namespace lapis::mesh_merge
