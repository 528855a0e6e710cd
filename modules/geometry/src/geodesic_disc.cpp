#include "lapis/geometry/geodesic_disc.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "lapis/core/error.h"
#include "lapis/geometry/dijkstra.h"

namespace lapis::geometry {

std::vector<int> geodesic_disc(const TriMesh& mesh, const Connectivity& conn, int seed, double radius) {
  if (seed < 0 || seed >= conn.num_vertices())
    throw InvalidArgument("geometry::geodesic_disc(): seed " + std::to_string(seed) + " out of range [0, " +
                          std::to_string(conn.num_vertices()) + ")");
  if (!(radius >= 0))
    throw InvalidArgument("geometry::geodesic_disc(): radius " + std::to_string(radius) +
                          ", expected a non-negative number");
  DijkstraOptions options;
  options.max_distance = radius;  // the search stops at the disc's rim
  const ShortestPaths paths = dijkstra(conn, {seed}, edge_length_cost(mesh), options);
  std::vector<int> disc;
  for (int v = 0; v < conn.num_vertices(); ++v)
    if (paths.distance[static_cast<size_t>(v)] <= radius) disc.push_back(v);
  return disc;
}

}  // namespace lapis::geometry
