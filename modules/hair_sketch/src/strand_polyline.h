// Polyline tools shared by the strand details: one strand as a vector of points, its arc
// lengths, resampling, rotation-minimizing frames, and a per-strand random stream.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace lapis::hair_sketch::detail {

using Polyline = std::vector<Eigen::Vector3f>;

// Cumulative arc length at each point (0 at the first).
std::vector<float> arc_lengths(const Polyline& p);
// The point at arc length s (clamped to [0, length]) of p with arc lengths `arc`.
Eigen::Vector3f point_at(const Polyline& p, const std::vector<float>& arc, float s);
// Points every `step` along p by arc length, and its last point.
Polyline resample(const Polyline& p, const std::vector<float>& arc, float step);
// p up to arc length s (its last point interpolated).
Polyline truncate(const Polyline& p, const std::vector<float>& arc, float s);

// Unit tangents and a rotation-minimizing frame along p (double reflection, Wang et al. 2008):
// normal[i] and binormal[i] turn as little as the curve lets them, so a helix about p does not
// twist where p bends. The first normal is first_normal made orthogonal to the first tangent.
struct Frames {
  std::vector<Eigen::Vector3f> tangent, normal, binormal;
};
Frames rotation_minimizing_frames(const Polyline& p, const Eigen::Vector3f& first_normal);

// 0 at s = 0 rising smoothly to 1 at s = fade (smoothstep); 1 when fade is 0.
float root_fade(float s, float fade);

// A random stream per (seed, strand, purpose): splitmix64 of the three, so a strand's draws do
// not depend on which thread handles it or on the other strands.
class StrandRandom {
 public:
  StrandRandom(std::uint32_t seed, int strand, std::uint32_t purpose);
  double uniform();  // [0, 1)
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

 private:
  std::uint64_t state_;
};

}  // namespace lapis::hair_sketch::detail
