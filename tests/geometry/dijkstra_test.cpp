// Dijkstra over mesh edges: exact on a grid, custom costs, early exit, bad costs.
#include <doctest/doctest.h>

#include <cmath>

#include "lapis/core/error.h"
#include "lapis/geometry/dijkstra.h"
#include "lapis/geometry/procedural.h"

using namespace lapis::geometry;

TEST_CASE("geometry: Dijkstra on a grid gives lattice distances and valid paths") {
  const int n = 10;
  const TriMesh grid = make_plane_grid(n, n, n, n);  // unit cells, diagonals from (i,j) to (i+1,j+1)
  const Connectivity conn(grid);
  const std::vector<int> source{0};
  const ShortestPaths sp = dijkstra(conn, source, edge_length_cost(grid));
  // With diagonals along (1, 1): distance to (i, j) is sqrt2 min(i, j) + |i - j|.
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      CHECK(sp.distance[j * (n + 1) + i] == doctest::Approx(std::sqrt(2.0) * std::min(i, j) + std::abs(i - j)));
  const int target = 4 * (n + 1) + 9;
  const std::vector<int> path = extract_path(sp, target);
  REQUIRE(path.size() >= 2);
  CHECK(path.front() == 0);
  CHECK(path.back() == target);
  double length = 0;
  for (size_t i = 1; i < path.size(); ++i) {
    REQUIRE(conn.find_edge(path[i - 1], path[i]) >= 0);
    length += (grid.V.row(path[i]) - grid.V.row(path[i - 1])).norm();
  }
  CHECK(length == doctest::Approx(sp.distance[target]));
}

TEST_CASE("geometry: Dijkstra with per-edge costs, limits and multiple sources") {
  const TriMesh grid = make_plane_grid(6, 1);
  const Connectivity conn(grid);
  // Forbid every edge touching x = 3 except the bottom one: the path must squeeze through.
  const EdgeCost cost = [&](int e, int, int) {
    const auto [a, b] = conn.edges()[e];
    const bool touches = grid.V(a, 0) == 0.5 || grid.V(b, 0) == 0.5;
    return touches && !(grid.V(a, 1) == 0 && grid.V(b, 1) == 0) ? std::numeric_limits<double>::infinity() : 1.0;
  };
  const std::vector<int> from{0};
  const ShortestPaths sp = dijkstra(conn, from, cost);
  const std::vector<int> path = extract_path(sp, 13);           // top right corner
  CHECK(std::find(path.begin(), path.end(), 3) != path.end());  // through the bottom vertex at x = 0.5
  // max_distance stops growth; target stops early.
  DijkstraOptions limited;
  limited.max_distance = 2.0;
  const ShortestPaths near = dijkstra(conn, from, cost, limited);
  CHECK(std::isinf(near.distance[6]));
  CHECK(extract_path(near, 6).empty());
  // Two sources split the strip between them.
  const std::vector<int> both{0, 6};
  const ShortestPaths two = dijkstra(grid, both);
  CHECK(two.distance[6] == 0.0);
  CHECK(two.distance[5] == doctest::Approx(1.0 / 6));
  CHECK_THROWS_WITH_AS(dijkstra(conn, from, [](int, int, int) { return -1.0; }),
                       doctest::Contains("geometry::dijkstra(): edge"), lapis::InvalidArgument);
  CHECK_THROWS_WITH_AS(dijkstra(conn, std::vector<int>{99}, cost),
                       "geometry::dijkstra(): source 99 out of range [0, 14)", lapis::InvalidArgument);
}
