#include "lapis/viewer/loop_picking.h"

#include <algorithm>

namespace lapis::viewer {
namespace {

struct Candidate {
  double pixels;
  int loop, position;
  Eigen::Vector3d point;  // the world point that must be visible
};

double segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b, double& t) {
  const Eigen::Vector2d d = b - a;
  const double len2 = d.squaredNorm();
  t = len2 > 0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (a + t * d - p).norm();
}

// Candidates come sorted by distance; the first visible one wins (the nearest drawn loop may
// be on the far side of the mesh).
LoopPick first_visible(std::vector<Candidate>& c, const geometry::CameraMatrices& camera,
                       const std::vector<std::vector<int>>& loops, const std::vector<const geometry::Bvh*>& occluders) {
  std::sort(c.begin(), c.end(), [](const Candidate& a, const Candidate& b) { return a.pixels < b.pixels; });
  for (const Candidate& k : c) {
    if (!visible(camera, k.point, occluders)) continue;
    LoopPick pick;
    pick.loop = k.loop;
    pick.position = k.position;
    pick.vertex = loops[static_cast<size_t>(k.loop)][static_cast<size_t>(k.position)];
    pick.pixels = k.pixels;
    return pick;
  }
  return {};
}

bool considered(const std::vector<int>& only, int loop) {
  return only.empty() || std::find(only.begin(), only.end(), loop) != only.end();
}

}  // namespace

bool visible(const geometry::CameraMatrices& camera, const Eigen::Vector3d& p,
             const std::vector<const geometry::Bvh*>& occluders) {
  const Eigen::Vector3d eye = geometry::eye_position(camera);
  const Eigen::Vector3d d = p - eye;
  const double dist = d.norm();
  if (!(dist > 0)) return true;
  // Boundary points sit on their own surface: allow hits up to 1% of the distance before them.
  const double t_max = dist * 0.99;
  for (const geometry::Bvh* bvh : occluders)
    if (bvh && bvh->intersect(eye, d / dist, t_max)) return false;
  return true;
}

LoopPick pick_loop(const geometry::CameraMatrices& camera, const geometry::Vertices& V,
                   const std::vector<std::vector<int>>& loops, double x, double y, double max_pixels,
                   const std::vector<const geometry::Bvh*>& occluders, const std::vector<int>& only) {
  const Eigen::Vector2d p(x, y);
  std::vector<Candidate> c;
  for (size_t l = 0; l < loops.size(); ++l) {
    if (!considered(only, static_cast<int>(l))) continue;
    const auto& loop = loops[l];
    const size_t n = loop.size();
    double best = max_pixels;
    int best_pos = -1;
    Eigen::Vector3d best_point;
    for (size_t i = 0; i < n; ++i) {
      const Eigen::Vector3d A = V.row(loop[i]).transpose(), B = V.row(loop[(i + 1) % n]).transpose();
      const Eigen::Vector3d a = geometry::project(camera, A), b = geometry::project(camera, B);
      if (a.z() <= 0 || a.z() >= 1 || b.z() <= 0 || b.z() >= 1) continue;  // behind the eye or clipped
      double t = 0;
      const double d = segment_distance(p, a.head<2>(), b.head<2>(), t);
      if (d > best) continue;
      best = d;
      best_pos = static_cast<int>(t < 0.5 ? i : (i + 1) % n);
      best_point = A + t * (B - A);
    }
    if (best_pos >= 0) c.push_back({best, static_cast<int>(l), best_pos, best_point});
  }
  return first_visible(c, camera, loops, occluders);
}

LoopPick pick_loop_vertex(const geometry::CameraMatrices& camera, const geometry::Vertices& V,
                          const std::vector<std::vector<int>>& loops, double x, double y, double max_pixels,
                          const std::vector<const geometry::Bvh*>& occluders, const std::vector<int>& only) {
  const Eigen::Vector2d p(x, y);
  std::vector<Candidate> c;
  for (size_t l = 0; l < loops.size(); ++l) {
    if (!considered(only, static_cast<int>(l))) continue;
    for (size_t i = 0; i < loops[l].size(); ++i) {
      const Eigen::Vector3d P = V.row(loops[l][i]).transpose();
      const Eigen::Vector3d s = geometry::project(camera, P);
      if (s.z() <= 0 || s.z() >= 1) continue;
      const double d = (s.head<2>() - p).norm();
      if (d <= max_pixels) c.push_back({d, static_cast<int>(l), static_cast<int>(i), P});
    }
  }
  return first_visible(c, camera, loops, occluders);
}

}  // namespace lapis::viewer
