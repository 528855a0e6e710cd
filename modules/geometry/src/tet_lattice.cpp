#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "lapis/core/error.h"
#include "lapis/geometry/tet_mesh.h"

namespace lapis::geometry {
namespace {

// The cubes of side h over the surface's box, with one empty layer around (the flood fill's
// outside), as a flag per cube: 1 occupied by the surface, 2 enclosed, 0 outside.
struct Lattice {
  Eigen::Vector3d origin;
  double h = 1;
  std::array<int, 3> dims{};  // cubes per axis, padding included
  std::vector<std::uint8_t> flag;
  size_t index(int x, int y, int z) const { return (static_cast<size_t>(z) * dims[1] + y) * dims[0] + x; }
};

void mark_point(Lattice& L, const Eigen::Vector3d& p) {
  std::array<int, 3> c{};
  for (int a = 0; a < 3; ++a)
    c[a] = std::clamp(static_cast<int>(std::floor((p[a] - L.origin[a]) / L.h)), 1, L.dims[a] - 2);
  L.flag[L.index(c[0], c[1], c[2])] = 1;
}

// Vertices, and points spaced at most h/2 apart on triangles longer than that.
void mark_surface(Lattice& L, const TriMesh& s) {
  for (int i = 0; i < s.num_vertices(); ++i) mark_point(L, s.V.row(i).transpose());
  for (int f = 0; f < s.num_faces(); ++f) {
    const Eigen::Vector3d a = s.V.row(s.F(f, 0)).transpose(), b = s.V.row(s.F(f, 1)).transpose(),
                          c = s.V.row(s.F(f, 2)).transpose();
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    const int m = static_cast<int>(std::ceil(longest / (0.5 * L.h)));
    if (m <= 1) continue;
    for (int i = 0; i <= m; ++i)
      for (int j = 0; i + j <= m; ++j) mark_point(L, a + (b - a) * (double(i) / m) + (c - a) * (double(j) / m));
  }
}

// Cubes not reachable from the padding through unoccupied cubes are enclosed.
void fill_enclosed(Lattice& L) {
  std::vector<std::uint8_t> outside(L.flag.size(), 0);
  std::vector<std::array<int, 3>> stack{{0, 0, 0}};
  outside[0] = 1;
  while (!stack.empty()) {
    const auto c = stack.back();
    stack.pop_back();
    static constexpr int step[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (const auto& s : step) {
      const int x = c[0] + s[0], y = c[1] + s[1], z = c[2] + s[2];
      if (x < 0 || y < 0 || z < 0 || x >= L.dims[0] || y >= L.dims[1] || z >= L.dims[2]) continue;
      const size_t k = L.index(x, y, z);
      if (outside[k] || L.flag[k]) continue;
      outside[k] = 1;
      stack.push_back({x, y, z});
    }
  }
  for (size_t k = 0; k < L.flag.size(); ++k)
    if (!L.flag[k] && !outside[k]) L.flag[k] = 2;
}

Lattice build_lattice(const TriMesh& s, double h) {
  Lattice L;
  L.h = h;
  const Eigen::Vector3d lo = s.V.colwise().minCoeff().transpose(), hi = s.V.colwise().maxCoeff().transpose();
  for (int a = 0; a < 3; ++a) L.dims[a] = static_cast<int>(std::floor((hi[a] - lo[a]) / h)) + 3;
  // Centre the cubes on the box, with a cube of padding on each side.
  for (int a = 0; a < 3; ++a) L.origin[a] = 0.5 * (lo[a] + hi[a]) - 0.5 * L.dims[a] * h;
  L.flag.assign(static_cast<size_t>(L.dims[0]) * L.dims[1] * L.dims[2], 0);
  mark_surface(L, s);
  fill_enclosed(L);
  return L;
}

// Lattice nodes of solid cubes: index per node, -1 elsewhere. Returns the count.
int number_nodes(const Lattice& L, std::vector<int>& node) {
  const int nx = L.dims[0] + 1, ny = L.dims[1] + 1;
  node.assign(static_cast<size_t>(nx) * ny * (L.dims[2] + 1), -1);
  int count = 0;
  for (int z = 0; z < L.dims[2]; ++z)
    for (int y = 0; y < L.dims[1]; ++y)
      for (int x = 0; x < L.dims[0]; ++x) {
        if (!L.flag[L.index(x, y, z)]) continue;
        for (int c = 0; c < 8; ++c) {
          int& id = node[(static_cast<size_t>(z + (c >> 2)) * ny + y + ((c >> 1) & 1)) * nx + x + (c & 1)];
          if (id < 0) id = count++;
        }
      }
  return count;
}

TetMesh to_tets(const Lattice& L) {
  std::vector<int> node;
  const int n = number_nodes(L, node);
  const int nx = L.dims[0] + 1, ny = L.dims[1] + 1;
  TetMesh m;
  m.V.resize(n, 3);
  for (int z = 0; z <= L.dims[2]; ++z)
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x)
        if (const int id = node[(static_cast<size_t>(z) * ny + y) * nx + x]; id >= 0)
          m.V.row(id) = (L.origin + L.h * Eigen::Vector3d(x, y, z)).transpose();
  std::vector<Eigen::RowVector4i> tets;
  static constexpr int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int z = 0; z < L.dims[2]; ++z)
    for (int y = 0; y < L.dims[1]; ++y)
      for (int x = 0; x < L.dims[0]; ++x) {
        if (!L.flag[L.index(x, y, z)]) continue;
        for (const auto& p : perms) {  // Kuhn: the path (0,0,0) → (1,1,1) along the axes in order p
          std::array<int, 3> c{x, y, z};
          Eigen::RowVector4i t;
          t[0] = node[(static_cast<size_t>(c[2]) * ny + c[1]) * nx + c[0]];
          for (int k = 0; k < 3; ++k) {
            ++c[p[k]];
            t[k + 1] = node[(static_cast<size_t>(c[2]) * ny + c[1]) * nx + c[0]];
          }
          const Eigen::Vector3d a = m.V.row(t[0]).transpose();
          if (tet_volume(a, m.V.row(t[1]).transpose(), m.V.row(t[2]).transpose(), m.V.row(t[3]).transpose()) < 0)
            std::swap(t[2], t[3]);
          tets.push_back(t);
        }
      }
  m.T.resize(static_cast<int>(tets.size()), 4);
  for (size_t t = 0; t < tets.size(); ++t) m.T.row(static_cast<int>(t)) = tets[t];
  return m;
}

}  // namespace

// Bisection on log h for the node count nearest target_vertices (the count falls as h grows,
// not strictly: the lattice's phase against the surface changes with h).
TetMesh lattice_enclosure(const TriMesh& surface, int target_vertices) {
  constexpr const char* fn = "geometry::lattice_enclosure()";
  require_valid(surface, {}, fn);
  if (surface.num_faces() == 0) throw InvalidArgument(std::string(fn) + ": the surface has no faces");
  if (target_vertices < 8)
    throw InvalidArgument(std::string(fn) + ": target_vertices = " + std::to_string(target_vertices) +
                          ", expected >= 8 (one cube)");
  const double extent = (surface.V.colwise().maxCoeff() - surface.V.colwise().minCoeff()).maxCoeff();
  double lo = std::log(extent / 512), hi = std::log(2 * extent);
  double best_h = std::exp(hi);
  int best_gap = -1;
  std::vector<int> node;
  for (int it = 0; it < 40; ++it) {
    const double mid = 0.5 * (lo + hi), h = std::exp(mid);
    const int count = number_nodes(build_lattice(surface, h), node);
    const int gap = std::abs(count - target_vertices);
    if (best_gap < 0 || gap < best_gap) {
      best_gap = gap;
      best_h = h;
    }
    (count > target_vertices ? lo : hi) = mid;
  }
  return to_tets(build_lattice(surface, best_h));
}

}  // namespace lapis::geometry
