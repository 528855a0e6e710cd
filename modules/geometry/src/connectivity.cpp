#include "lapis/geometry/connectivity.h"

#include <algorithm>
#include <string>

#include "lapis/core/error.h"

namespace lapis::geometry {

AdjacencyLists vertex_face_lists(const Faces& F, int num_vertices) {
  AdjacencyLists lists;
  lists.offsets.assign(num_vertices + 1, 0);
  auto repeated = [&](Eigen::Index f, int k) { return (k > 0 && F(f, 0) == F(f, k)) || (k > 1 && F(f, 1) == F(f, k)); };
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (!repeated(f, k)) ++lists.offsets[F(f, k) + 1];
  for (int v = 0; v < num_vertices; ++v) lists.offsets[v + 1] += lists.offsets[v];
  lists.items.resize(lists.offsets[num_vertices]);
  std::vector<int> fill(lists.offsets.begin(), lists.offsets.end() - 1);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (!repeated(f, k)) lists.items[fill[F(f, k)]++] = static_cast<int>(f);
  return lists;
}

Connectivity::Connectivity(const TriMesh& mesh) : F_(mesh.F), num_vertices_(mesh.num_vertices()) {
  require_indices_in_range(mesh, "geometry::Connectivity()");
  vertex_faces_ = vertex_face_lists(F_, num_vertices_);
  build_edges();
  build_boundary_loops();
}

// Half-edges are bucketed by their lower vertex (counting sort), then each small bucket is
// sorted by the upper vertex: linear time, no hash map, edges come out ordered by (a, b).
void Connectivity::build_edges() {
  const int nf = num_faces(), nv = num_vertices_;
  struct Half {
    int hi, face, corner;
  };
  std::vector<int> offsets(nv + 1, 0);
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) ++offsets[std::min(F_(f, k), F_(f, (k + 1) % 3)) + 1];
  for (int v = 0; v < nv; ++v) offsets[v + 1] += offsets[v];
  std::vector<Half> halves(offsets[nv]);
  std::vector<int> fill(offsets.begin(), offsets.end() - 1);
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = F_(f, k), b = F_(f, (k + 1) % 3);
      halves[fill[std::min(a, b)]++] = {std::max(a, b), f, k};
    }
  face_edges_.assign(3 * static_cast<size_t>(nf), -1);
  edges_.reserve(halves.size() / 2 + 1);  // closed manifold: exactly half the half-edges
  edge_faces_.reserve(halves.size() / 2 + 1);
  edge_face_count_.reserve(halves.size() / 2 + 1);
  for (int v = 0; v < nv; ++v) {
    auto begin = halves.begin() + offsets[v], end = halves.begin() + offsets[v + 1];
    std::sort(begin, end,
              [](const Half& x, const Half& y) { return x.hi < y.hi || (x.hi == y.hi && x.face < y.face); });
    for (auto it = begin; it != end; ++it) {
      if (it == begin || it->hi != (it - 1)->hi) {
        edges_.push_back({v, it->hi});
        edge_faces_.push_back({it->face, -1});
        edge_face_count_.push_back(0);
      }
      const int e = static_cast<int>(edges_.size()) - 1;
      if (edge_face_count_[e] == 1) edge_faces_[e][1] = it->face;
      ++edge_face_count_[e];
      face_edges_[3 * static_cast<size_t>(it->face) + it->corner] = e;
    }
  }
  // Vertex-vertex lists: edges are sorted by (a, b), so appending b to a's list in edge order
  // and a to b's list in edge order gives ascending lists without another sort.
  std::vector<int> deg(nv + 1, 0);
  for (const auto& e : edges_) {
    ++deg[e[0] + 1];
    if (e[1] != e[0]) ++deg[e[1] + 1];
  }
  for (int v = 0; v < nv; ++v) deg[v + 1] += deg[v];
  vertex_neighbors_.offsets = deg;
  vertex_neighbors_.items.resize(deg[nv]);
  vertex_edges_.offsets = deg;
  vertex_edges_.items.resize(deg[nv]);
  std::vector<int> pos(deg.begin(), deg.end() - 1);
  for (int pass = 0; pass < 2; ++pass)  // pass 0: lower neighbours (a of edges (a, v)); 1: upper
    for (int e = 0; e < num_edges(); ++e) {
      const int a = edges_[e][0], b = edges_[e][1];
      if (a == b) {
        if (pass == 0) vertex_neighbors_.items[pos[a]] = a, vertex_edges_.items[pos[a]++] = e;
        continue;
      }
      const int owner = pass == 0 ? b : a, other = pass == 0 ? a : b;
      vertex_neighbors_.items[pos[owner]] = other;
      vertex_edges_.items[pos[owner]++] = e;
    }
  is_boundary_vertex_.assign(nv, 0);
  for (int e = 0; e < num_edges(); ++e)
    if (edge_face_count_[e] == 1) is_boundary_vertex_[edges_[e][0]] = is_boundary_vertex_[edges_[e][1]] = 1;
}

// Boundary half-edges keep their face's direction; loops follow them vertex to vertex. At a
// pinch vertex (two boundary half-edges leave it) the first unused one is taken.
void Connectivity::build_boundary_loops() {
  std::vector<int> out_offsets(num_vertices_ + 1, 0);
  std::vector<std::array<int, 2>> halves;  // (from, to)
  for (int f = 0; f < num_faces(); ++f)
    for (int k = 0; k < 3; ++k)
      if (edge_face_count_[face_edge(f, k)] == 1) halves.push_back({F_(f, k), F_(f, (k + 1) % 3)});
  for (const auto& h : halves) ++out_offsets[h[0] + 1];
  for (int v = 0; v < num_vertices_; ++v) out_offsets[v + 1] += out_offsets[v];
  std::vector<int> out(halves.size()), fill(out_offsets.begin(), out_offsets.end() - 1);
  for (int h = 0; h < static_cast<int>(halves.size()); ++h) out[fill[halves[h][0]]++] = h;
  std::vector<char> used(halves.size(), 0);
  for (size_t start = 0; start < halves.size(); ++start) {
    if (used[start]) continue;
    std::vector<int> loop;
    int h = static_cast<int>(start);
    while (h >= 0 && !used[h]) {
      used[h] = 1;
      loop.push_back(halves[h][0]);
      const int v = halves[h][1];
      if (v == halves[start][0]) break;
      h = -1;
      for (int i = out_offsets[v]; i < out_offsets[v + 1]; ++i)
        if (!used[out[i]]) {
          h = out[i];
          break;
        }
    }
    boundary_loops_.push_back(std::move(loop));
  }
}

int Connectivity::find_edge(int a, int b) const {
  const auto n = vertex_neighbors(a);
  const auto it = std::lower_bound(n.begin(), n.end(), b);
  if (it == n.end() || *it != b) return -1;
  return vertex_edges(a)[it - n.begin()];
}

int Connectivity::face_neighbor(int f, int k) const {
  const int e = face_edge(f, k);
  if (edge_face_count_[e] != 2) return -1;
  return edge_faces_[e][0] == f ? edge_faces_[e][1] : edge_faces_[e][0];
}

std::vector<int> Connectivity::one_ring_ordered(int v) const {
  // Around v, face (v, a, b) turns from a to b: successor[a] = b.
  std::vector<std::array<int, 2>> next;
  for (int f : vertex_faces(v)) {
    int k = 0;
    while (F_(f, k) != v) ++k;
    next.push_back({F_(f, (k + 1) % 3), F_(f, (k + 2) % 3)});
  }
  auto fail = [&] {
    throw InvalidArgument("geometry::Connectivity::one_ring_ordered(): vertex " + std::to_string(v) +
                          " is non-manifold: its faces do not form a single fan");
  };
  if (next.empty()) return {};
  std::sort(next.begin(), next.end());
  for (size_t i = 1; i < next.size(); ++i)
    if (next[i][0] == next[i - 1][0]) fail();
  auto successor = [&](int a) {
    const auto it = std::lower_bound(next.begin(), next.end(), std::array<int, 2>{a, -1});
    return it != next.end() && (*it)[0] == a ? (*it)[1] : -1;
  };
  // An open fan starts at the one 'a' that is nobody's successor.
  std::vector<int> targets;
  for (const auto& n : next) targets.push_back(n[1]);
  std::sort(targets.begin(), targets.end());
  int start = next[0][0];
  for (const auto& n : next)
    if (!std::binary_search(targets.begin(), targets.end(), n[0])) start = n[0];
  std::vector<int> ring{start};
  for (int cur = successor(start); cur >= 0 && cur != start; cur = successor(cur)) {
    ring.push_back(cur);
    if (ring.size() > next.size() + 1) fail();
  }
  const bool closed = successor(ring.back()) == start;
  if (ring.size() != next.size() + (closed ? 0 : 1)) fail();
  return ring;
}

}  // namespace lapis::geometry
