#include "lapis/viewer/colormap.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace lapis::viewer {
namespace {

// Stops of the map, evenly spaced (close to matplotlib's "turbo" at these points, without its
// dark ends, so shading stays readable on a lit surface).
const Eigen::Vector3f kStops[] = {{0.19f, 0.29f, 0.80f}, {0.16f, 0.65f, 0.90f}, {0.20f, 0.82f, 0.56f},
                                  {0.75f, 0.87f, 0.24f}, {0.98f, 0.62f, 0.15f}, {0.85f, 0.18f, 0.12f}};
constexpr int kLast = sizeof(kStops) / sizeof(kStops[0]) - 1;

}  // namespace

Eigen::Vector3f colormap(double t) {
  if (std::isnan(t)) return {0.5f, 0.5f, 0.5f};
  const double x = std::clamp(t, 0.0, 1.0) * kLast;
  const int i = std::min(static_cast<int>(x), kLast - 1);
  const float f = static_cast<float>(x - i);
  return (1 - f) * kStops[i] + f * kStops[i + 1];
}

Points3f colorize(const Eigen::VectorXd& values, double lo, double hi) {
  Points3f out(values.size(), 3);
  const double span = hi - lo;
  for (Eigen::Index i = 0; i < values.size(); ++i)
    out.row(i) = colormap(span > 0 ? (values(i) - lo) / span : 0.0).transpose();
  return out;
}

double percentile(const Eigen::VectorXd& values, double fraction) {
  std::vector<double> v;
  v.reserve(static_cast<size_t>(values.size()));
  for (Eigen::Index i = 0; i < values.size(); ++i)
    if (std::isfinite(values(i))) v.push_back(values(i));
  if (v.empty()) return 0;
  const size_t k =
      std::min(v.size() - 1, static_cast<size_t>(std::clamp(fraction, 0.0, 1.0) * static_cast<double>(v.size())));
  std::nth_element(v.begin(), v.begin() + static_cast<long>(k), v.end());
  return v[k];
}

}  // namespace lapis::viewer
