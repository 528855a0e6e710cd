// Graph queries over Connectivity: k-rings, components, Euler characteristic, genus.
#include <numeric>
#include <string>

#include "lapis/core/error.h"
#include "lapis/geometry/connectivity.h"

namespace lapis::geometry {

std::vector<int> k_ring(const Connectivity& conn, const std::vector<int>& seeds, int k) {
  if (k < 0) throw InvalidArgument("geometry::k_ring(): k = " + std::to_string(k) + ", expected k >= 0");
  std::vector<int> dist(conn.num_vertices(), -1), order;
  for (int s : seeds) {
    if (s < 0 || s >= conn.num_vertices())
      throw InvalidArgument("geometry::k_ring(): seed " + std::to_string(s) + " out of range [0, " +
                            std::to_string(conn.num_vertices()) + ")");
    if (dist[s] < 0) dist[s] = 0, order.push_back(s);
  }
  for (size_t head = 0; head < order.size(); ++head) {
    const int v = order[head];
    if (dist[v] == k) continue;
    for (int w : conn.vertex_neighbors(v))
      if (dist[w] < 0) dist[w] = dist[v] + 1, order.push_back(w);
  }
  return order;
}

Components connected_components(const Connectivity& conn) {
  // Union-find over vertices through face edges: components touching only at a vertex are one.
  std::vector<int> parent(conn.num_vertices());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (const auto& e : conn.edges()) {
    const int a = find(e[0]), b = find(e[1]);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
  Components c;
  c.vertex_component.assign(conn.num_vertices(), -1);
  std::vector<int> label(conn.num_vertices(), -1);
  for (int v = 0; v < conn.num_vertices(); ++v) {
    if (conn.is_isolated_vertex(v)) continue;
    const int r = find(v);
    if (label[r] < 0) label[r] = c.count++;
    c.vertex_component[v] = label[r];
  }
  c.face_component.resize(conn.num_faces());
  for (int f = 0; f < conn.num_faces(); ++f)
    c.face_component[f] = c.vertex_component[conn.edges()[conn.face_edge(f, 0)][0]];
  return c;
}

int euler_characteristic(const Connectivity& conn) {
  int used = 0;
  for (int v = 0; v < conn.num_vertices(); ++v) used += !conn.is_isolated_vertex(v);
  return used - conn.num_edges() + conn.num_faces();
}

int genus(const Connectivity& conn) {
  const int c = connected_components(conn).count;
  const int b = static_cast<int>(conn.boundary_loops().size());
  return (2 * c - euler_characteristic(conn) - b) / 2;
}

Components connected_components(const TriMesh& mesh) { return connected_components(Connectivity(mesh)); }
int euler_characteristic(const TriMesh& mesh) { return euler_characteristic(Connectivity(mesh)); }
int genus(const TriMesh& mesh) { return genus(Connectivity(mesh)); }

}  // namespace lapis::geometry
