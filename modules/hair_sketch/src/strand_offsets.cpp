// Curls, waves and frizz: offsets about the grown curve that fade in from the root.
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "strand_detail_ops.h"

namespace lapis::hair_sketch::detail {

Eigen::Vector3f keep_clear(const Eigen::Vector3f& from, const Eigen::Vector3f& to, const DetailContext& context) {
  if (!context.clearance) return to;
  const HeadClearance& clearance = *context.clearance;
  const double at_to = clearance(to);
  if (at_to >= context.min_clearance) return to;
  const double at_from = clearance(from);
  // Where growth left the strand inside the head, detail leaves it be: wound about a point
  // inside, it would cross the scalp back and forth.
  if (at_from < 0) return from;
  if (at_to >= at_from) return to;  // no closer than the grown strand already is
  const double floor = std::min<double>(context.min_clearance, at_from);
  Eigen::Vector3f offset = to - from;
  for (int halving = 0; halving < 4; ++halving) {
    offset *= 0.5f;
    if (clearance(from + offset) >= floor) return from + offset;
  }
  return from;
}

namespace {

constexpr float kTwoPi = 2 * std::numbers::pi_v<float>;
constexpr int kMaxPoints = 4000;  // per strand: a curl finer than this is sampled coarser

float mean_step(const std::vector<float>& arc) { return arc.back() / static_cast<float>(arc.size() - 1); }

// Samples p at most at `step`, no more than kMaxPoints.
Polyline refine(const Polyline& p, const std::vector<float>& arc, float step) {
  step = std::max(step, arc.back() / kMaxPoints);
  return step < mean_step(arc) ? resample(p, arc, step) : p;
}

// A grown strand sampled finer for an offset detail: the points, their arc lengths, and the
// grown strand's length (t = arc / length).
struct Sampled {
  Polyline points;
  std::vector<float> arc;
  float length = 0;
};
Sampled sample_finer(const Polyline& grown, float step) {
  const std::vector<float> grown_arc = arc_lengths(grown);
  Sampled s;
  s.length = grown_arc.back();
  s.points = s.length > 0 ? refine(grown, grown_arc, step) : grown;
  s.arc = arc_lengths(s.points);
  return s;
}

Eigen::Vector3f outward(const Polyline& p, const DetailContext& context) { return p.front() - context.center; }

}  // namespace

Polyline curl_strand(const CurlDetail& d, std::uint32_t seed, int index, const Polyline& grown,
                     const DetailContext& context) {
  if (d.radius == 0) return grown;  // bit-identical to no detail
  // At least 12 points per turn where the frequency peaks.
  const float peak = static_cast<float>(d.frequency * std::max(1.0, 1.0 + d.frequency_growth));
  const Sampled sampled = sample_finer(grown, 1 / (12 * peak));
  const float length = sampled.length;
  if (!(length > 0)) return grown;
  const Polyline& p = sampled.points;
  const std::vector<float>& arc = sampled.arc;
  // The normal starts along the scalp's outward direction, so a wave (along the binormal)
  // swings across the strand within the layer of hair, as neighbouring strands do.
  const Frames frames = rotation_minimizing_frames(p, outward(p, context));
  StrandRandom random(seed, index, 1);
  float phase = static_cast<float>(random.uniform(0, d.phase_jitter * kTwoPi));
  const float radius = static_cast<float>(d.radius * random.uniform(1 - d.radius_jitter, 1 + d.radius_jitter));
  Polyline out(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    const float t = arc[i] / length;
    if (i > 0) {
      const float t_mid = 0.5f * (arc[i] + arc[i - 1]) / length;
      phase += kTwoPi * static_cast<float>(d.frequency * (1 + d.frequency_growth * t_mid)) * (arc[i] - arc[i - 1]);
    }
    const float r =
        radius * static_cast<float>(1 + d.radius_growth * t) * root_fade(arc[i], static_cast<float>(d.root_fade));
    const Eigen::Vector3f offset =
        d.helical ? Eigen::Vector3f(r * (std::cos(phase) * frames.normal[i] + std::sin(phase) * frames.binormal[i]))
                  : Eigen::Vector3f(r * std::sin(phase) * frames.binormal[i]);
    out[i] = keep_clear(p[i], p[i] + offset, context);
  }
  return out;
}

namespace {

// Catmull–Rom through knots[k-1..k+2] at u in [0, 1] between knots k and k+1.
Eigen::Vector3f catmull_rom(const std::vector<Eigen::Vector3f>& knots, int k, float u) {
  const Eigen::Vector3f& p0 = knots[k - 1];
  const Eigen::Vector3f& p1 = knots[k];
  const Eigen::Vector3f& p2 = knots[k + 1];
  const Eigen::Vector3f& p3 = knots[k + 2];
  const float u2 = u * u, u3 = u2 * u;
  return 0.5f * (2 * p1 + (p2 - p0) * u + (2 * p0 - 5 * p1 + 4 * p2 - p3) * u2 + (3 * p1 - p0 - 3 * p2 + p3) * u3);
}

}  // namespace

Polyline frizz_strand(const FrizzDetail& d, std::uint32_t seed, int index, const Polyline& grown,
                      const DetailContext& context) {
  if (d.amplitude == 0) return grown;  // bit-identical to no detail
  const float wavelength = static_cast<float>(d.wavelength);
  const Sampled sampled = sample_finer(grown, wavelength / 4);
  if (!(sampled.length > 0)) return grown;
  const Polyline& p = sampled.points;
  const std::vector<float>& arc = sampled.arc;
  const int spans = static_cast<int>(std::ceil(arc.back() / wavelength)) + 1;
  // Knot k sits at arc length (k − 1)·wavelength: one extra knot each side for Catmull–Rom.
  std::vector<Eigen::Vector3f> knots(spans + 3);
  StrandRandom random(seed, index, 2);
  const double a = d.amplitude;
  for (auto& k : knots)
    k = Eigen::Vector3d(random.uniform(-a, a), random.uniform(-a, a), random.uniform(-a, a)).cast<float>();
  Polyline out(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    const float x = arc[i] / wavelength;
    const int span = std::min(static_cast<int>(x), spans - 1);
    const Eigen::Vector3f offset =
        root_fade(arc[i], static_cast<float>(d.root_fade)) * catmull_rom(knots, span + 1, x - static_cast<float>(span));
    out[i] = keep_clear(p[i], p[i] + offset, context);
  }
  return out;
}

}  // namespace lapis::hair_sketch::detail
