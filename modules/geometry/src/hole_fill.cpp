#include "lapis/geometry/hole_fill.h"

#include <algorithm>
#include <limits>
#include <string>

#include <Eigen/Geometry>

#include "lapis/core/error.h"

namespace lapis::geometry {
namespace {

constexpr const char* kFn = "geometry::minimal_area_fill()";

void check_loop(const Vertices& V, const std::vector<int>& loop) {
  if (loop.size() < 3)
    throw InvalidArgument(std::string(kFn) + ": a hole needs at least 3 corners, got " + std::to_string(loop.size()));
  std::vector<int> sorted = loop;
  for (int v : loop)
    if (v < 0 || v >= V.rows())
      throw InvalidArgument(std::string(kFn) + ": corner " + std::to_string(v) + " is out of range [0, " +
                            std::to_string(V.rows()) + ")");
  std::sort(sorted.begin(), sorted.end());
  const auto twice = std::adjacent_find(sorted.begin(), sorted.end());
  if (twice != sorted.end())
    throw InvalidArgument(std::string(kFn) + ": corner " + std::to_string(*twice) + " appears twice in the loop");
}

double triangle_area(const Vertices& V, int a, int b, int c) {
  return 0.5 * (V.row(b) - V.row(a)).cross(V.row(c) - V.row(a)).norm();
}

HoleFill centroid_fan(const Vertices& V, const std::vector<int>& loop) {
  const int k = static_cast<int>(loop.size());
  HoleFill fill;
  fill.fan = true;
  fill.added = Vertices::Zero(1, 3);
  for (int v : loop) fill.added.row(0) += V.row(v);
  fill.added.row(0) /= k;
  Vertices all(V.rows() + 1, 3);
  all.topRows(V.rows()) = V;
  all.row(V.rows()) = fill.added.row(0);
  const int centre = static_cast<int>(V.rows());
  fill.faces.resize(k, 3);
  for (int i = 0; i < k; ++i) {
    const int a = loop[i], b = loop[(i + 1) % k];
    fill.faces.row(i) << b, a, centre;  // against the loop, like the area-minimal faces
    fill.area += triangle_area(all, a, b, centre);
  }
  return fill;
}

}  // namespace

HoleFill minimal_area_fill(const Vertices& V, const std::vector<int>& loop, int max_exact_corners) {
  check_loop(V, loop);
  const int k = static_cast<int>(loop.size());
  if (k > max_exact_corners) return centroid_fan(V, loop);
  // best[i][j]: least area of the sub-polygon loop[i..j]; split[i][j]: its apex corner.
  const size_t n = static_cast<size_t>(k);
  std::vector<double> best(n * n, 0.0);
  std::vector<int> split(n * n, -1);
  for (int len = 2; len < k; ++len)
    for (int i = 0; i + len < k; ++i) {
      const int j = i + len;
      double least = std::numeric_limits<double>::infinity();
      int apex = -1;
      for (int m = i + 1; m < j; ++m) {
        const double a = best[i * n + m] + best[m * n + j] + triangle_area(V, loop[i], loop[m], loop[j]);
        // Lower by a relative margin: near-equal areas keep the earlier apex.
        if (apex < 0 || a < least - 1e-12 * least) least = a, apex = m;
      }
      best[i * n + j] = least;
      split[i * n + j] = apex;
    }
  HoleFill fill;
  fill.area = best[n - 1];
  fill.faces.resize(k - 2, 3);
  int next = 0;
  std::vector<std::pair<int, int>> pending{{0, k - 1}};
  while (!pending.empty()) {
    const auto [i, j] = pending.back();
    pending.pop_back();
    if (j - i < 2) continue;
    const int m = split[i * n + j];
    fill.faces.row(next++) << loop[i], loop[j], loop[m];  // against the loop's direction
    pending.push_back({i, m});
    pending.push_back({m, j});
  }
  return fill;
}

}  // namespace lapis::geometry
