// Bvh queries: nearest ray hit, closest point, inside test. Traversal keeps an explicit
// stack and visits the nearer child first so that far subtrees are culled by the best so far.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "lapis/core/error.h"
#include "lapis/core/format.h"
#include "lapis/geometry/bvh.h"

namespace lapis::geometry {

std::optional<std::pair<double, Eigen::Vector3d>> intersect_triangle(const Eigen::Vector3d& origin,
                                                                     const Eigen::Vector3d& direction,
                                                                     const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                                                     const Eigen::Vector3d& c) {
  // Moller & Trumbore 1997.
  const Eigen::Vector3d e1 = b - a, e2 = c - a;
  const Eigen::Vector3d p = direction.cross(e2);
  const double det = e1.dot(p);
  if (det == 0 || !std::isfinite(det)) return std::nullopt;
  const double inv = 1.0 / det;
  const Eigen::Vector3d s = origin - a;
  const double u = s.dot(p) * inv;
  if (u < 0 || u > 1) return std::nullopt;
  const Eigen::Vector3d q = s.cross(e1);
  const double v = direction.dot(q) * inv;
  if (v < 0 || u + v > 1) return std::nullopt;
  const double t = e2.dot(q) * inv;
  if (t < 0) return std::nullopt;
  return std::make_pair(t, Eigen::Vector3d(1 - u - v, u, v));
}

Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                          const Eigen::Vector3d& c) {
  // Ericson 5.1.5: find the Voronoi region of p among vertices, edges and the face.
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return {1 - v, v, 0};
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return {1 - w, 0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - w, w};
  }
  const double sum = va + vb + vc;
  if (!(sum > 0)) return {1, 0, 0};  // degenerate triangle: its first corner will do
  const double v = vb / sum, w = vc / sum;
  return {1 - v - w, v, w};
}

namespace {
// Slab test: entry distance of the ray into the box, or +inf when it misses within t_max.
inline double ray_box(const double lo[3], const double hi[3], const Eigen::Vector3d& o, const Eigen::Vector3d& inv,
                      double t_max) {
  double t0 = 0, t1 = t_max;
  for (int k = 0; k < 3; ++k) {
    double a = (lo[k] - o[k]) * inv[k], b = (hi[k] - o[k]) * inv[k];
    if (a > b) std::swap(a, b);
    // NaN from 0 * inf (ray in the slab plane) must not cull: std::max/min keep t0/t1 then.
    t0 = a > t0 ? a : t0;
    t1 = b < t1 ? b : t1;
  }
  return t0 <= t1 ? t0 : std::numeric_limits<double>::infinity();
}

inline double box_distance2(const double lo[3], const double hi[3], const Eigen::Vector3d& p) {
  double d = 0;
  for (int k = 0; k < 3; ++k) {
    const double e = std::max({lo[k] - p[k], 0.0, p[k] - hi[k]});
    d += e * e;
  }
  return d;
}
}  // namespace

std::optional<RayHit> Bvh::intersect(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                                     double t_max) const {
  if (mesh_.num_faces() == 0 || !origin.allFinite() || !direction.allFinite() || direction.isZero())
    return std::nullopt;
  const Eigen::Vector3d inv = direction.cwiseInverse();
  constexpr double kMiss = std::numeric_limits<double>::infinity();
  RayHit best;
  best.t = t_max;
  // Each stack entry keeps its box entry distance, tested when pushed: on pop it is only
  // compared with the best hit found since, instead of intersecting the box again.
  std::pair<int, double> stack[128];
  int top = 0;
  const double t_root = ray_box(nodes_[0].lo, nodes_[0].hi, origin, inv, t_max);
  if (t_root != kMiss) stack[top++] = {0, t_root};
  while (top > 0) {
    const auto [index, t_enter] = stack[--top];
    if (t_enter > best.t) continue;
    const Node& n = nodes_[index];
    if (n.count > 0) {
      for (int i = n.first; i < n.first + n.count; ++i) {
        const int f = order_[i];
        const auto hit = intersect_triangle(origin, direction, mesh_.V.row(mesh_.F(f, 0)), mesh_.V.row(mesh_.F(f, 1)),
                                            mesh_.V.row(mesh_.F(f, 2)));
        if (hit && (hit->first < best.t || (hit->first == best.t && (best.face < 0 || f < best.face)))) {
          best.face = f;
          best.t = hit->first;
          best.barycentric = hit->second;
        }
      }
      continue;
    }
    // Push the farther child first so the nearer one is popped next.
    const Node& l = nodes_[n.first];
    const Node& r = nodes_[n.first + 1];
    const double tl = ray_box(l.lo, l.hi, origin, inv, best.t), tr = ray_box(r.lo, r.hi, origin, inv, best.t);
    const bool left_first = tl <= tr;
    const double t_near = left_first ? tl : tr, t_far = left_first ? tr : tl;
    if (t_far != kMiss) stack[top++] = {left_first ? n.first + 1 : n.first, t_far};
    if (t_near != kMiss) stack[top++] = {left_first ? n.first : n.first + 1, t_near};
  }
  if (best.face < 0) return std::nullopt;
  best.point = origin + best.t * direction;
  return best;
}

ClosestPoint Bvh::closest_point(const Eigen::Vector3d& p) const {
  if (mesh_.num_faces() == 0) throw InvalidArgument("geometry::Bvh::closest_point(): the mesh has no faces");
  if (!p.allFinite()) throw InvalidArgument("geometry::Bvh::closest_point(): query point is not finite");
  ClosestPoint best;
  double best_d2 = std::numeric_limits<double>::infinity();
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    if (box_distance2(n.lo, n.hi, p) >= best_d2) continue;
    if (n.count > 0) {
      for (int i = n.first; i < n.first + n.count; ++i) {
        const int f = order_[i];
        const Eigen::Vector3d a = mesh_.V.row(mesh_.F(f, 0)), b = mesh_.V.row(mesh_.F(f, 1)),
                              c = mesh_.V.row(mesh_.F(f, 2));
        const Eigen::Vector3d w = closest_point_on_triangle(p, a, b, c);
        const Eigen::Vector3d q = w[0] * a + w[1] * b + w[2] * c;
        const double d2 = (q - p).squaredNorm();
        if (d2 < best_d2 || (d2 == best_d2 && f < best.face)) {
          best_d2 = d2;
          best.face = f;
          best.barycentric = w;
          best.point = q;
        }
      }
      continue;
    }
    const double dl = box_distance2(nodes_[n.first].lo, nodes_[n.first].hi, p);
    const double dr = box_distance2(nodes_[n.first + 1].lo, nodes_[n.first + 1].hi, p);
    stack[top++] = dl <= dr ? n.first + 1 : n.first;
    stack[top++] = dl <= dr ? n.first : n.first + 1;
  }
  // Every squared distance overflowed: p is beyond 1e154 of every face.
  if (best.face < 0)
    throw InvalidArgument("geometry::Bvh::closest_point(): query point (" + format_number(p.x()) + ", " +
                          format_number(p.y()) + ", " + format_number(p.z()) +
                          ") is so far from the mesh that its squared distance overflows");
  best.distance = std::sqrt(best_d2);
  return best;
}

int Bvh::count_crossings(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction) const {
  const Eigen::Vector3d inv = direction.cwiseInverse();
  int crossings = 0;
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    if (ray_box(n.lo, n.hi, origin, inv, std::numeric_limits<double>::infinity()) ==
        std::numeric_limits<double>::infinity())
      continue;
    if (n.count > 0) {
      for (int i = n.first; i < n.first + n.count; ++i) {
        const int f = order_[i];
        crossings += intersect_triangle(origin, direction, mesh_.V.row(mesh_.F(f, 0)), mesh_.V.row(mesh_.F(f, 1)),
                                        mesh_.V.row(mesh_.F(f, 2)))
                         .has_value();
      }
      continue;
    }
    stack[top++] = n.first;
    stack[top++] = n.first + 1;
  }
  return crossings;
}

bool Bvh::inside(const Eigen::Vector3d& p) const {
  if (mesh_.num_faces() == 0 || !p.allFinite()) return false;
  // Directions with irrational-looking components rarely graze edges of real meshes.
  static const Eigen::Vector3d dirs[3] = {{0.5773502691896258, 0.5773502691896257, 0.5773502691896259},
                                          {-0.2672612419124244, 0.5345224838248488, 0.8017837257372732},
                                          {0.8164965809277261, -0.4082482904638631, -0.4082482904638630}};
  int votes = 0;
  for (const auto& d : dirs) votes += count_crossings(p, d) % 2;
  return votes >= 2;
}

int Bvh::depth() const {
  if (mesh_.num_faces() == 0) return 0;
  int deepest = 0;
  std::vector<std::pair<int, int>> stack{{0, 1}};
  while (!stack.empty()) {
    const auto [node, d] = stack.back();
    stack.pop_back();
    deepest = std::max(deepest, d);
    if (nodes_[node].count == 0)
      stack.push_back({nodes_[node].first, d + 1}), stack.push_back({nodes_[node].first + 1, d + 1});
  }
  return deepest;
}

}  // namespace lapis::geometry
