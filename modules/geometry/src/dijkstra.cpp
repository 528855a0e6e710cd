#include "lapis/geometry/dijkstra.h"

#include <cmath>
#include <queue>
#include <string>

#include "lapis/core/error.h"

namespace lapis::geometry {

ShortestPaths dijkstra(const Connectivity& conn, const std::vector<int>& sources, const EdgeCost& cost,
                       const DijkstraOptions& options) {
  const int n = conn.num_vertices();
  ShortestPaths out;
  out.distance.assign(n, std::numeric_limits<double>::infinity());
  out.predecessor.assign(n, -1);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> heap;
  for (int s : sources) {
    if (s < 0 || s >= n)
      throw InvalidArgument("geometry::dijkstra(): source " + std::to_string(s) + " out of range [0, " +
                            std::to_string(n) + ")");
    out.distance[s] = 0;
    heap.push({0.0, s});
  }
  std::vector<char> settled(n, 0);
  while (!heap.empty()) {
    const auto [d, v] = heap.top();
    heap.pop();
    if (settled[v] || d > out.distance[v]) continue;  // a stale entry
    settled[v] = 1;
    if (v == options.target) break;
    const auto neighbors = conn.vertex_neighbors(v);
    const auto edges = conn.vertex_edges(v);
    for (size_t i = 0; i < neighbors.size(); ++i) {
      const int w = neighbors[i];
      if (settled[w]) continue;
      const double c = cost(edges[i], v, w);
      if (!(c >= 0))
        throw InvalidArgument("geometry::dijkstra(): edge " + std::to_string(edges[i]) + " (" + std::to_string(v) +
                              ", " + std::to_string(w) + ") has cost " + std::to_string(c) +
                              ", expected a non-negative number");
      const double nd = d + c;
      if (nd < out.distance[w] && nd <= options.max_distance) {
        out.distance[w] = nd;
        out.predecessor[w] = v;
        heap.push({nd, w});
      }
    }
  }
  return out;
}

EdgeCost edge_length_cost(const TriMesh& mesh) {
  return [&mesh](int, int from, int to) { return (mesh.V.row(from) - mesh.V.row(to)).norm(); };
}

ShortestPaths dijkstra(const TriMesh& mesh, const std::vector<int>& sources, const EdgeCost& cost,
                       const DijkstraOptions& options) {
  return dijkstra(Connectivity(mesh), sources, cost ? cost : edge_length_cost(mesh), options);
}

std::vector<int> extract_path(const ShortestPaths& paths, int target) {
  if (target < 0 || target >= static_cast<int>(paths.distance.size()))
    throw InvalidArgument("geometry::extract_path(): target " + std::to_string(target) + " out of range [0, " +
                          std::to_string(paths.distance.size()) + ")");
  if (!std::isfinite(paths.distance[target])) return {};
  std::vector<int> path;
  for (int v = target; v >= 0; v = paths.predecessor[v]) {
    path.push_back(v);
    if (path.size() > paths.predecessor.size())
      throw InvalidArgument("geometry::extract_path(): predecessors form a cycle");
  }
  return {path.rbegin(), path.rend()};
}

}  // namespace lapis::geometry
