#include "strand_polyline.h"

#include <algorithm>
#include <cmath>

namespace lapis::hair_sketch::detail {

std::vector<float> arc_lengths(const Polyline& p) {
  std::vector<float> arc(p.size(), 0.f);
  for (std::size_t i = 1; i < p.size(); ++i) arc[i] = arc[i - 1] + (p[i] - p[i - 1]).norm();
  return arc;
}

Eigen::Vector3f point_at(const Polyline& p, const std::vector<float>& arc, float s) {
  if (s <= 0 || p.size() == 1) return p.front();
  if (s >= arc.back()) return p.back();
  const auto it = std::upper_bound(arc.begin(), arc.end(), s);
  const std::size_t i = static_cast<std::size_t>(it - arc.begin());  // arc[i-1] <= s < arc[i]
  const float len = arc[i] - arc[i - 1];
  const float w = len > 0 ? (s - arc[i - 1]) / len : 0.f;
  return (1 - w) * p[i - 1] + w * p[i];
}

Polyline resample(const Polyline& p, const std::vector<float>& arc, float step) {
  const float length = arc.back();
  const int n = std::max(1, static_cast<int>(std::ceil(length / step)));
  Polyline out;
  out.reserve(n + 1);
  // Walk the segments once instead of a binary search per sample.
  std::size_t seg = 1;
  for (int k = 0; k <= n; ++k) {
    const float s = std::min(length, length * static_cast<float>(k) / static_cast<float>(n));
    while (seg + 1 < p.size() && arc[seg] < s) ++seg;
    const float len = arc[seg] - arc[seg - 1];
    const float w = len > 0 ? std::clamp((s - arc[seg - 1]) / len, 0.f, 1.f) : 0.f;
    out.push_back((1 - w) * p[seg - 1] + w * p[seg]);
  }
  return out;
}

Polyline truncate(const Polyline& p, const std::vector<float>& arc, float s) {
  if (s >= arc.back()) return p;
  Polyline out;
  std::size_t i = 0;
  while (i < p.size() && arc[i] < s) out.push_back(p[i++]);
  out.push_back(point_at(p, arc, s));
  if (out.size() < 2) out.push_back(out.front());  // a cut at the root keeps a zero-length strand
  return out;
}

namespace {

Eigen::Vector3f any_perpendicular(const Eigen::Vector3f& t) {
  const Eigen::Vector3f a = std::abs(t.x()) < 0.6f ? Eigen::Vector3f::UnitX() : Eigen::Vector3f::UnitY();
  return t.cross(a).normalized();
}

Eigen::Vector3f reflect(const Eigen::Vector3f& x, const Eigen::Vector3f& v, float c) {
  return c > 1e-20f ? Eigen::Vector3f(x - (2 / c) * v.dot(x) * v) : x;
}

}  // namespace

Frames rotation_minimizing_frames(const Polyline& p, const Eigen::Vector3f& first_normal) {
  const std::size_t n = p.size();
  Frames f;
  f.tangent.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3f d = p[std::min(i + 1, n - 1)] - p[i > 0 ? i - 1 : 0];
    f.tangent[i] = d.norm() > 0 ? d.normalized() : (i > 0 ? f.tangent[i - 1] : Eigen::Vector3f::UnitY());
  }
  f.normal.resize(n);
  f.binormal.resize(n);
  Eigen::Vector3f r = first_normal - first_normal.dot(f.tangent[0]) * f.tangent[0];
  r = r.norm() > 1e-6f ? r.normalized() : any_perpendicular(f.tangent[0]);
  f.normal[0] = r;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const Eigen::Vector3f v1 = p[i + 1] - p[i];
    const Eigen::Vector3f rl = reflect(f.normal[i], v1, v1.squaredNorm());
    const Eigen::Vector3f tl = reflect(f.tangent[i], v1, v1.squaredNorm());
    const Eigen::Vector3f v2 = f.tangent[i + 1] - tl;
    Eigen::Vector3f next = reflect(rl, v2, v2.squaredNorm());
    next -= next.dot(f.tangent[i + 1]) * f.tangent[i + 1];  // float drift
    f.normal[i + 1] = next.norm() > 1e-6f ? next.normalized() : any_perpendicular(f.tangent[i + 1]);
  }
  for (std::size_t i = 0; i < n; ++i) f.binormal[i] = f.tangent[i].cross(f.normal[i]);
  return f;
}

float root_fade(float s, float fade) {
  if (fade <= 0) return 1.f;
  const float x = std::clamp(s / fade, 0.f, 1.f);
  return x * x * (3 - 2 * x);
}

namespace {

std::uint64_t splitmix(std::uint64_t& x) {
  std::uint64_t z = (x += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

}  // namespace

StrandRandom::StrandRandom(std::uint32_t seed, int strand, std::uint32_t purpose)
    : state_((static_cast<std::uint64_t>(seed) << 32) ^ static_cast<std::uint32_t>(strand)) {
  std::uint64_t s = state_ ^ (static_cast<std::uint64_t>(purpose) * 0xD1B54A32D192ED03ull);
  state_ = splitmix(s);
}

double StrandRandom::uniform() { return static_cast<double>(splitmix(state_) >> 11) * 0x1.0p-53; }

}  // namespace lapis::hair_sketch::detail
