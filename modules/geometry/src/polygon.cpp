// triangulate_polygon(): the max-min-angle triangulation of a polygon by dynamic programming
// over its sub-polygons (Klincsek 1980), with a best-fan shortcut for long polygons.
#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Geometry>

#include "lapis/core/error.h"
#include "lapis/geometry/mesh_edit.h"

namespace lapis::geometry {
namespace {

constexpr const char* kFn = "geometry::triangulate_polygon()";

// Above this many corners the O(k³) program gives way to the best fan, O(k²).
constexpr size_t kMaxProgramCorners = 160;

// The smallest angle of triangle (a, b, c) in radians; 0 for a degenerate one.
double smallest_angle(const Vertices& V, int a, int b, int c) {
  const Eigen::Vector3d p = V.row(a).transpose(), q = V.row(b).transpose(), r = V.row(c).transpose();
  const auto angle = [](const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
    const double s = u.cross(v).norm(), d = u.dot(v);
    return s > 0 || d > 0 ? std::atan2(s, d) : 0.0;
  };
  return std::min({angle(q - p, r - p), angle(p - q, r - q), angle(p - r, q - r)});
}

// x larger than y by more than rounding: near-equal angles are ties, which go to the earlier
// split so that a similarity of the positions does not change the triangles.
bool larger(double x, double y) { return x > y + 1e-12; }

Faces best_fan(const Vertices& V, const std::vector<int>& p) {
  const size_t k = p.size();
  size_t apex = 0;
  double best = -1;
  for (size_t a = 0; a < k; ++a) {
    double worst = 4;
    for (size_t t = 1; t + 1 < k; ++t)
      worst = std::min(worst, smallest_angle(V, p[a], p[(a + t) % k], p[(a + t + 1) % k]));
    if (larger(worst, best)) best = worst, apex = a;
  }
  Faces F(static_cast<Eigen::Index>(k - 2), 3);
  for (size_t t = 1; t + 1 < k; ++t)
    F.row(static_cast<Eigen::Index>(t - 1)) << p[apex], p[(apex + t) % k], p[(apex + t + 1) % k];
  return F;
}

Faces max_min_angle(const Vertices& V, const std::vector<int>& p) {
  const size_t k = p.size();
  // best[i·k + j]: the largest smallest angle over triangulations of corners i..j (j ≥ i + 2);
  // split[i·k + j] the third corner of the triangle on the chord (i, j).
  std::vector<double> best(k * k, 4.0);
  std::vector<int> split(k * k, -1);
  for (size_t span = 2; span < k; ++span)
    for (size_t i = 0; i + span < k; ++i) {
      const size_t j = i + span;
      double b = -1;
      for (size_t m = i + 1; m < j; ++m) {
        const double q = std::min({best[i * k + m], best[m * k + j], smallest_angle(V, p[i], p[m], p[j])});
        if (larger(q, b)) b = q, split[i * k + j] = static_cast<int>(m);
      }
      best[i * k + j] = b;
    }
  Faces F(static_cast<Eigen::Index>(k - 2), 3);
  Eigen::Index n = 0;
  std::vector<std::pair<size_t, size_t>> chords{{0, k - 1}};
  while (!chords.empty()) {
    const auto [i, j] = chords.back();
    chords.pop_back();
    if (j < i + 2) continue;
    const size_t m = static_cast<size_t>(split[i * k + j]);
    F.row(n++) << p[i], p[m], p[j];
    chords.push_back({i, m});
    chords.push_back({m, j});
  }
  return F;
}

}  // namespace

Faces triangulate_polygon(const Vertices& V, const std::vector<int>& polygon) {
  if (polygon.size() < 3)
    throw InvalidArgument(std::string(kFn) + ": polygon has " + std::to_string(polygon.size()) +
                          " corners, expected at least 3");
  for (int v : polygon)
    if (v < 0 || v >= V.rows())
      throw InvalidArgument(std::string(kFn) + ": vertex " + std::to_string(v) + " out of range [0, " +
                            std::to_string(V.rows()) + ")");
  return polygon.size() > kMaxProgramCorners ? best_fan(V, polygon) : max_min_angle(V, polygon);
}

}  // namespace lapis::geometry
