#include "lapis/mesh_merge/refine.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "lapis/geometry/connectivity.h"
#include "lapis/geometry/mesh_edit.h"

namespace lapis::mesh_merge {

int split_boundary_edges(geometry::TriMesh& mesh) {
  const geometry::Connectivity conn(mesh);
  std::vector<Eigen::RowVector3i> faces;
  std::vector<Eigen::RowVector3d> added;
  const int n = mesh.num_vertices();
  for (int f = 0; f < mesh.num_faces(); ++f) {
    int k = 0;
    while (k < 3 && !conn.is_boundary_edge(conn.face_edge(f, k))) ++k;
    if (k == 3) {
      faces.push_back(mesh.F.row(f));
      continue;
    }
    // Only the first boundary edge of a face is split: a face with two boundary edges (an ear)
    // keeps the other one, and the next level catches it.
    const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3), c = mesh.F(f, (k + 2) % 3);
    const int m = n + static_cast<int>(added.size());
    added.push_back(0.5 * (mesh.V.row(a) + mesh.V.row(b)));
    faces.emplace_back(a, m, c);
    faces.emplace_back(m, b, c);
  }
  mesh.V.conservativeResize(n + static_cast<Eigen::Index>(added.size()), 3);
  for (size_t i = 0; i < added.size(); ++i) mesh.V.row(n + static_cast<Eigen::Index>(i)) = added[i];
  mesh.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (size_t i = 0; i < faces.size(); ++i) mesh.F.row(static_cast<Eigen::Index>(i)) = faces[i];
  return static_cast<int>(added.size());
}

int refine_short_boundary(geometry::TriMesh& mesh, double min_ratio, int max_levels) {
  int levels = 0;
  while (levels < max_levels) {
    const geometry::Connectivity conn(mesh);
    size_t boundary = 0;
    for (const auto& loop : conn.boundary_loops()) boundary += loop.size();
    if (boundary == 0 || double(boundary) >= min_ratio * std::sqrt(double(mesh.num_vertices()))) break;
    split_boundary_edges(mesh);
    ++levels;
  }
  return levels;
}

namespace {

// Whether the positions (on a cycle of n) form one run of consecutive positions.
bool one_run(std::vector<int> positions, int n) {
  if (positions.size() <= 1 || static_cast<int>(positions.size()) >= n) return true;
  std::sort(positions.begin(), positions.end());
  int gaps = positions.front() + n - positions.back() > 1;
  for (size_t i = 1; i < positions.size(); ++i) gaps += positions[i] - positions[i - 1] > 1;
  return gaps <= 1;
}

// How many separate sectors of faces touching a merging loop the faces around c form: two
// or more, and removing the ring next to the loop leaves c on the inner loop twice, even where
// c's loop neighbours are consecutive on the loop.
template <class IsMerging>
int touching_sectors(const geometry::TriMesh& mesh, const geometry::Connectivity& conn, int c,
                     const IsMerging& is_merging) {
  const auto touches = [&](int f) {
    if (f < 0) return false;
    for (int k = 0; k < 3; ++k)
      if (is_merging(mesh.F(f, k))) return true;
    return false;
  };
  int faces = 0, around = 0, joined = 0;
  for (int f : conn.vertex_faces(c)) faces += touches(f), ++around;
  for (int e : conn.vertex_edges(c)) {
    const auto [f, g] = conn.edge_faces(e);
    joined += touches(f) && touches(g);
  }
  return faces == around ? 1 : faces - joined;
}

// The edges whose split separates a pinch next to a merging loop: edges off the loops between
// two loop vertices (of one loop, not neighbours on it, or of two loops, the mesh's other
// boundary loops included), and the edges from the loops to a vertex whose loop neighbours are
// on two loops or are not one run of one loop.
std::vector<std::pair<int, int>> pinching_edges(const geometry::TriMesh& mesh,
                                                const std::vector<std::vector<int>>& merging) {
  const geometry::Connectivity conn(mesh);
  std::vector<std::vector<int>> loops;  // the merging loops first, then the mesh's other borders
  std::vector<int> loop_of(static_cast<size_t>(mesh.num_vertices()), -1), position(loop_of.size(), -1);
  const auto add = [&](const std::vector<int>& loop) {
    for (int v : loop)
      if (loop_of[v] >= 0) return;  // a merging loop again
    for (size_t i = 0; i < loop.size(); ++i)
      loop_of[loop[i]] = static_cast<int>(loops.size()), position[loop[i]] = static_cast<int>(i);
    loops.push_back(loop);
  };
  for (const auto& loop : merging) add(loop);
  const int merging_count = static_cast<int>(loops.size());
  for (const auto& loop : conn.boundary_loops()) add(loop);
  const auto is_merging = [&](int v) { return loop_of[v] >= 0 && loop_of[v] < merging_count; };
  std::vector<std::pair<int, int>> out;
  for (int e = 0; e < conn.num_edges(); ++e) {
    const auto [a, b] = conn.edges()[e];
    if (conn.is_boundary_edge(e) || loop_of[a] < 0 || loop_of[b] < 0 || !(is_merging(a) || is_merging(b))) continue;
    const int n = static_cast<int>(loops[loop_of[a]].size()), d = std::abs(position[a] - position[b]);
    if (loop_of[a] != loop_of[b] || (d != 1 && d != n - 1)) out.emplace_back(a, b);
  }
  for (int c = 0; c < mesh.num_vertices(); ++c) {
    if (loop_of[c] >= 0) continue;
    int loop = -1;
    bool pinched = false, merging_near = false;
    std::vector<int> positions;
    for (const int w : conn.vertex_neighbors(c)) {
      if (loop_of[w] < 0) continue;
      if (loop >= 0 && loop_of[w] != loop) pinched = true;
      loop = loop_of[w];
      merging_near |= is_merging(w);
      positions.push_back(position[w]);
    }
    if (!merging_near || (!pinched && one_run(positions, static_cast<int>(loops[loop].size())) &&
                          touching_sectors(mesh, conn, c, is_merging) <= 1))
      continue;
    for (const int w : conn.vertex_neighbors(c))
      if (loop_of[w] >= 0) out.emplace_back(w, c);
  }
  return out;
}

}  // namespace

int separate_loop_neighbourhoods(geometry::TriMesh& mesh, const std::vector<std::vector<int>>& loops, int max_rounds) {
  int added = 0;
  for (int round = 0; round < max_rounds; ++round) {
    const std::vector<std::pair<int, int>> edges = pinching_edges(mesh, loops);
    if (edges.empty()) break;
    added += geometry::split_edges(mesh, edges);
  }
  return added;
}

}  // namespace lapis::mesh_merge
