#include <algorithm>
#include <numeric>
#include <unordered_map>

#include "lapis/mesh_deform/isolines.h"

namespace lapis::mesh_deform {
namespace {

std::int64_t edge_key(int a, int b, std::int64_t n) { return std::min(a, b) * n + std::max(a, b); }

IsolinePoint at_vertex(int corner, int v, std::int64_t n) {
  IsolinePoint p;
  p.b[corner] = 1;
  p.key = edge_key(v, v, n);
  return p;
}

// Where the level s crosses the face's edge from corner i to corner j (f_i ≠ f_j, s between them).
IsolinePoint on_edge(int i, int j, const std::array<double, 3>& f, const std::array<int, 3>& v, double s,
                     std::int64_t n) {
  IsolinePoint p;
  const double t = (s - f[i]) / (f[j] - f[i]);
  p.b[i] = 1 - t;
  p.b[j] = t;
  p.key = edge_key(v[i], v[j], n);
  return p;
}

int side(double f, double s) { return (f > s) - (f < s); }

// The segment of level s in one face, if any.
bool face_segment(const std::array<double, 3>& f, const std::array<int, 3>& v, double s, std::int64_t n,
                  IsolinePoint& p, IsolinePoint& q) {
  const std::array<int, 3> sd{side(f[0], s), side(f[1], s), side(f[2], s)};
  const int on = (sd[0] == 0) + (sd[1] == 0) + (sd[2] == 0);
  if (on == 3) return false;  // inside a flat region
  if (on == 2) {
    // The level runs along an edge: both faces of the edge see it, and only the one whose third
    // corner lies above counts it (below at the top level s = 1, where none lies above).
    const int k = sd[0] != 0 ? 0 : sd[1] != 0 ? 1 : 2;
    if (sd[k] != (s >= 1.0 ? -1 : 1)) return false;
    p = at_vertex((k + 1) % 3, v[(k + 1) % 3], n);
    q = at_vertex((k + 2) % 3, v[(k + 2) % 3], n);
    return true;
  }
  if (on == 1) {
    // Through a vertex: a segment to the opposite edge if its ends lie on both sides, else a touch.
    const int k = sd[0] == 0 ? 0 : sd[1] == 0 ? 1 : 2, i = (k + 1) % 3, j = (k + 2) % 3;
    if (sd[i] == sd[j]) return false;
    p = at_vertex(k, v[k], n);
    q = on_edge(i, j, f, v, s, n);
    return true;
  }
  if (sd[0] == sd[1] && sd[1] == sd[2]) return false;
  // The lone corner k lies on one side, the other two on the other.
  const int k = sd[0] != sd[1] && sd[0] != sd[2] ? 0 : sd[1] != sd[0] ? 1 : 2;
  p = on_edge(k, (k + 1) % 3, f, v, s, n);
  q = on_edge(k, (k + 2) % 3, f, v, s, n);
  return true;
}

}  // namespace

Eigen::Vector3d isoline_point(const geometry::Vertices& V, const geometry::Faces& F, int face, const IsolinePoint& p) {
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k)
    if (p.b[k] != 0) x += p.b[k] * V.row(F(face, k)).transpose();
  return x;
}

std::vector<IsolineSegment> extract_isolines(const geometry::Vertices& V, const geometry::Faces& F,
                                             const Eigen::VectorXd& field, const std::vector<double>& isovalues) {
  const std::int64_t n = V.rows();
  std::vector<IsolineSegment> out;
  for (int face = 0; face < F.rows(); ++face) {
    const std::array<int, 3> v{F(face, 0), F(face, 1), F(face, 2)};
    const std::array<double, 3> f{field(v[0]), field(v[1]), field(v[2])};
    const double lo = std::min({f[0], f[1], f[2]}), hi = std::max({f[0], f[1], f[2]});
    for (int level = 0; level < static_cast<int>(isovalues.size()); ++level) {
      const double s = isovalues[level];
      if (s < lo || s > hi) continue;
      IsolineSegment seg;
      if (!face_segment(f, v, s, n, seg.p, seg.q)) continue;
      seg.face = face;
      seg.level = level;
      seg.length = (isoline_point(V, F, face, seg.p) - isoline_point(V, F, face, seg.q)).norm();
      out.push_back(seg);
    }
  }
  return out;
}

int count_isoline_loops(const std::vector<IsolineSegment>& segments, int level) {
  std::unordered_map<std::int64_t, int> node;
  std::vector<int> parent;
  auto id = [&](std::int64_t key) {
    auto [it, fresh] = node.try_emplace(key, static_cast<int>(parent.size()));
    if (fresh) parent.push_back(it->second);
    return it->second;
  };
  auto find = [&](int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (const auto& seg : segments)
    if (seg.level == level) {
      const int a = find(id(seg.p.key)), b = find(id(seg.q.key));
      parent[a] = b;
    }
  int loops = 0;
  for (int x = 0; x < static_cast<int>(parent.size()); ++x) loops += find(x) == x;
  return loops;
}

}  // namespace lapis::mesh_deform
