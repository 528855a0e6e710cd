// Shortest paths over mesh edges with a caller-given cost per edge: the optimal merging
// boundary (thesis §3.4.3: a shortest closed path under per-edge boundary energy) and
// geodesic-ish distance fields for transition regions (§3.3.3, edge-length costs).
#pragma once

#include <functional>
#include <limits>
#include <vector>

#include "lapis/geometry/connectivity.h"
#include "lapis/geometry/tri_mesh.h"

namespace lapis::geometry {

struct ShortestPaths {
  std::vector<double> distance;  // #V; +inf where unreachable (or beyond max_distance)
  std::vector<int> predecessor;  // #V; previous vertex on a shortest path, -1 at sources/unreached
};

// Cost of walking along edge e (conn.edges()[e]) from vertex `from` to vertex `to`; must
// be >= 0 and not NaN (+inf forbids the edge).
using EdgeCost = std::function<double(int e, int from, int to)>;

struct DijkstraOptions {
  double max_distance = std::numeric_limits<double>::infinity();  // stop growing beyond this
  int target = -1;  // stop once this vertex is settled (-1: settle everything reachable)
};

// Multi-source Dijkstra with a binary heap (lazy deletion). Throws InvalidArgument for a
// source out of range or a negative / NaN edge cost (naming the edge).
ShortestPaths dijkstra(const Connectivity& conn, const std::vector<int>& sources, const EdgeCost& cost,
                       const DijkstraOptions& options = {});

// Builds the connectivity of mesh first. An empty cost means edge lengths: distances along
// edges, an upper bound of the geodesic distance.
ShortestPaths dijkstra(const TriMesh& mesh, const std::vector<int>& sources, const EdgeCost& cost = {},
                       const DijkstraOptions& options = {});

// Cost functor of Euclidean edge lengths of mesh (keeps a reference to mesh).
EdgeCost edge_length_cost(const TriMesh& mesh);

// Vertices from a source to target along predecessors; empty when target was not reached.
std::vector<int> extract_path(const ShortestPaths& paths, int target);

}  // namespace lapis::geometry
