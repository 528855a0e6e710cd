#include "lapis/geometry/mesh_edit.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <unordered_map>

#include "lapis/core/error.h"

namespace lapis::geometry {
namespace {

// Replaces each index by map[index], drops faces that now repeat an index, then drops
// unused vertices; returns the composed old-to-new map.
std::vector<int> remap_faces(TriMesh& mesh, const std::vector<int>& map) {
  Faces kept(mesh.F.rows(), 3);
  Eigen::Index n = 0;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const int a = map[mesh.F(f, 0)], b = map[mesh.F(f, 1)], c = map[mesh.F(f, 2)];
    if (a != b && b != c && c != a) kept.row(n++) << a, b, c;
  }
  mesh.F = kept.topRows(n);
  const std::vector<int> compact = remove_unreferenced_vertices(mesh);
  std::vector<int> total(map.size());
  for (size_t v = 0; v < map.size(); ++v) total[v] = compact[map[v]];
  return total;
}

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  }
  void join(int a, int b) {
    a = find(a), b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);  // the lowest index represents
  }
};

void check_vertex(const TriMesh& mesh, int v, const char* fn) {
  if (v < 0 || v >= mesh.num_vertices())
    throw InvalidArgument(std::string(fn) + ": vertex " + std::to_string(v) + " out of range [0, " +
                          std::to_string(mesh.num_vertices()) + ")");
}

}  // namespace

std::vector<int> remove_unreferenced_vertices(TriMesh& mesh) {
  std::vector<int> map(mesh.num_vertices(), -1);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) map[mesh.F(f, k)] = 0;
  int n = 0;
  for (int v = 0; v < mesh.num_vertices(); ++v)
    if (map[v] == 0) {
      mesh.V.row(n) = mesh.V.row(v);
      map[v] = n++;
    }
  mesh.V.conservativeResize(n, 3);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) mesh.F(f, k) = map[mesh.F(f, k)];
  return map;
}

std::vector<int> vertices_of_faces(const TriMesh& mesh, const std::vector<int>& faces) {
  std::vector<int> out;
  for (int f : faces)
    if (f >= 0 && f < mesh.num_faces())
      for (int j = 0; j < 3; ++j) out.push_back(mesh.F(f, j));
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

TriMesh with_faces(const TriMesh& mesh, const std::vector<int>& faces) {
  TriMesh out;
  out.V = mesh.V;
  out.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (size_t i = 0; i < faces.size(); ++i) {
    if (faces[i] < 0 || faces[i] >= mesh.num_faces())
      throw InvalidArgument("geometry::with_faces(): face " + std::to_string(faces[i]) + " is out of range [0, " +
                            std::to_string(mesh.num_faces()) + ")");
    out.F.row(static_cast<Eigen::Index>(i)) = mesh.F.row(faces[i]);
  }
  return out;
}

TriMesh remove_faces(const TriMesh& mesh, const std::vector<int>& faces, std::vector<int>* vertex_map) {
  require_indices_in_range(mesh, "geometry::remove_faces()");
  std::vector<char> removed(mesh.num_faces(), 0);
  for (int f : faces) {
    if (f < 0 || f >= mesh.num_faces())
      throw InvalidArgument("geometry::remove_faces(): face " + std::to_string(f) + " out of range [0, " +
                            std::to_string(mesh.num_faces()) + ")");
    removed[f] = 1;
  }
  TriMesh out;
  out.V = mesh.V;
  out.F.resize(mesh.num_faces() - std::count(removed.begin(), removed.end(), 1), 3);
  Eigen::Index n = 0;
  for (int f = 0; f < mesh.num_faces(); ++f)
    if (!removed[f]) out.F.row(n++) = mesh.F.row(f);
  std::vector<int> map = remove_unreferenced_vertices(out);
  if (vertex_map) *vertex_map = std::move(map);
  return out;
}

std::vector<int> weld_vertices(TriMesh& mesh, double tolerance) {
  if (!(tolerance >= 0) || !std::isfinite(tolerance))
    throw InvalidArgument("geometry::weld_vertices(): tolerance " + std::to_string(tolerance) +
                          ", expected a finite value >= 0");
  require_indices_in_range(mesh, "geometry::weld_vertices()");
  UnionFind uf(mesh.num_vertices());
  // Cells of size tolerance: any partner within tolerance lies in one of the 27 cells around.
  const double cell = tolerance > 0 ? tolerance : 1.0;
  auto key = [](long long x, long long y, long long z) {
    return static_cast<std::uint64_t>(x * 73856093LL ^ y * 19349663LL ^ z * 83492791LL);
  };
  std::unordered_multimap<std::uint64_t, int> grid;
  grid.reserve(mesh.num_vertices());
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const Eigen::RowVector3d p = mesh.V.row(v);
    const long long cx = std::llround(std::floor(p.x() / cell)), cy = std::llround(std::floor(p.y() / cell)),
                    cz = std::llround(std::floor(p.z() / cell));
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy)
        for (long long dz = -1; dz <= 1; ++dz) {
          const auto range = grid.equal_range(key(cx + dx, cy + dy, cz + dz));
          for (auto it = range.first; it != range.second; ++it)
            if ((mesh.V.row(it->second) - p).norm() <= tolerance) uf.join(it->second, v);
        }
    grid.emplace(key(cx, cy, cz), v);
  }
  std::vector<int> map(mesh.num_vertices());
  for (int v = 0; v < mesh.num_vertices(); ++v) map[v] = uf.find(v);
  return remap_faces(mesh, map);
}

std::vector<int> weld_vertex_pairs(TriMesh& mesh, const std::vector<std::pair<int, int>>& pairs) {
  require_indices_in_range(mesh, "geometry::weld_vertex_pairs()");
  UnionFind uf(mesh.num_vertices());
  for (const auto& [p, q] : pairs) {
    check_vertex(mesh, p, "geometry::weld_vertex_pairs()");
    check_vertex(mesh, q, "geometry::weld_vertex_pairs()");
    uf.join(p, q);
  }
  std::vector<int> map(mesh.num_vertices()), count(mesh.num_vertices(), 0);
  Vertices sum = Vertices::Zero(mesh.num_vertices(), 3);
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    map[v] = uf.find(v);
    sum.row(map[v]) += mesh.V.row(v);
    ++count[map[v]];
  }
  for (int v = 0; v < mesh.num_vertices(); ++v)
    if (count[v] > 1) mesh.V.row(v) = sum.row(v) / count[v];
  return remap_faces(mesh, map);
}

}  // namespace lapis::geometry
