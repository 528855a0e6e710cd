#include "lapis/hair_sketch/ponytail.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "curve_sampling.h"
#include "lapis/core/error.h"
#include "lapis/core/format.h"

namespace lapis::hair_sketch {
using hair_field::Constraint;
using hair_field::Grid;

namespace {

// At most this many points on all cross-section rings together (a ponytail across a grid of
// 1e9 unknowns needs about a million).
constexpr double kMaxRingPoints = 1 << 22;

// Arc-length parameterized spine: nearest-point projection and evaluation.
struct Spine {
  std::vector<Eigen::Vector3d> p;  // resampled
  double h;
  // Arc length of the spine point nearest q, and its distance.
  std::pair<double, double> project(const Eigen::Vector3d& q) const {
    double best = 1e300, s = 0;
    for (size_t i = 0; i + 1 < p.size(); ++i) {
      const Eigen::Vector3d d = p[i + 1] - p[i];
      const double t = std::clamp((q - p[i]).dot(d) / d.squaredNorm(), 0.0, 1.0);
      const double dist = (p[i] + t * d - q).norm();
      if (dist < best) best = dist, s = (i + t) * h;
    }
    return {s, best};
  }
  Eigen::Vector3d at(double s) const {
    const double f = std::clamp(s / h, 0.0, static_cast<double>(p.size() - 1) - 1e-9);
    const size_t i = static_cast<size_t>(f);
    return p[i] + (f - i) * (p[i + 1] - p[i]);
  }
  Eigen::Vector3d tangent(double s) const {
    const double f = std::clamp(s / h, 0.0, static_cast<double>(p.size() - 1) - 1e-9);
    const size_t i = static_cast<size_t>(f);
    return (p[i + 1] - p[i]).normalized();
  }
  double length() const { return h * (p.size() - 1); }
};

Spine make_spine(const std::vector<Eigen::Vector3d>& spine, double h) {
  return {detail::resample(spine, h, "hair_sketch::Ponytail::constraints()"), h};
}

// Radius along the spine from a profile curve: (arc length, distance) pairs sorted by s.
std::vector<std::pair<double, double>> profile_radii(const Spine& sp, const std::vector<Eigen::Vector3d>& prof) {
  std::vector<std::pair<double, double>> r;
  for (const auto& q : prof) r.push_back(sp.project(q));
  std::sort(r.begin(), r.end());
  return r;
}

double interpolate(const std::vector<std::pair<double, double>>& r, double s) {
  if (s <= r.front().first) return r.front().second;
  if (s >= r.back().first) return r.back().second;
  auto it = std::lower_bound(r.begin(), r.end(), std::make_pair(s, -1e300));
  const auto& b = *it;
  const auto& a = *(it - 1);
  const double t = b.first > a.first ? (s - a.first) / (b.first - a.first) : 0.0;
  return a.second + t * (b.second - a.second);
}

// Points sampling the annulus r1..r2 on C1's plane, at most half a spacing apart.
double annulus_radii(double r1, double r2, double d) { return std::max(2.0, std::ceil((r2 - r1) / (0.5 * d)) + 1); }
double annulus_ring_points(double rho, double d) {
  return std::max(8.0, std::ceil(2 * std::numbers::pi * rho / (0.5 * d)));
}

// The nodes nearest those points, each pointing at the spine within C1's plane with magnitude
// `magnitude` (off-plane nodes do not point back against the tail).
void centripetal_ring(const Grid& grid, const Ponytail::Section& c1, double r1, double r2, double magnitude,
                      std::vector<Constraint>& out) {
  const double d = grid.spacing;
  Eigen::Vector3d u, v;
  detail::orthonormal_frame(c1.normal, u, v);
  std::vector<Constraint> nearest;
  const int radii = static_cast<int>(annulus_radii(r1, r2, d));  // bounded by kMaxRingPoints
  for (int a = 0; a < radii; ++a) {
    const double rho = r1 + (r2 - r1) * a / (radii - 1);
    const int n = static_cast<int>(annulus_ring_points(rho, d));
    for (int k = 0; k < n; ++k) {
      const double phi = 2 * std::numbers::pi * k / n;
      detail::constrain_nearest(grid, c1.center + rho * (std::cos(phi) * u + std::sin(phi) * v),
                                Eigen::Vector3d::Zero(), nearest);
    }
  }
  std::vector<int> nodes;
  for (const auto& c : nearest) nodes.push_back(c.node);
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  for (const int node : nodes) {
    const Eigen::Vector3d q = grid.position(node) - c1.center;
    const Eigen::Vector3d radial = q - q.dot(c1.normal) * c1.normal;
    // Not inside the annulus' inner circle: nodes between C1 and R1 pointing inward made a
    // sink there, where strands stopped (a tail of the bundled half_up session).
    if (radial.norm() >= r1) out.push_back({node, -magnitude * radial.normalized()});
  }
}

}  // namespace

Ponytail::Section Ponytail::first_section() const {
  if (cross_section.size() < 3)
    throw InvalidArgument("hair_sketch::Ponytail: the cross section needs at least 3 points");
  double length = 0;
  for (size_t i = 1; i < spine.size(); ++i) length += (spine[i] - spine[i - 1]).norm();
  const Spine sp = make_spine(spine, std::max(length / 200, 1e-9));
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& q : cross_section) c += q;
  c /= static_cast<double>(cross_section.size());
  const double s = sp.project(c).first;
  Section sec{sp.at(s), sp.tangent(s), 0.0};
  for (const auto& q : cross_section) {
    const Eigen::Vector3d v = q - sec.center;
    sec.radius += (v - v.dot(sec.normal) * sec.normal).norm();
  }
  sec.radius /= static_cast<double>(cross_section.size());
  if (!(sec.radius > 0)) throw InvalidArgument("hair_sketch::Ponytail: zero cross-section radius");
  return sec;
}

std::vector<Constraint> Ponytail::constraints(const Grid& grid) const {
  if (profile_a.size() < 2 || profile_b.size() < 2)
    throw InvalidArgument("hair_sketch::Ponytail::constraints(): profiles need at least 2 points");
  const double d = grid.spacing;
  const Spine sp = make_spine(spine, d);
  const Section c1 = first_section();
  const double s1 = sp.project(c1.center).first;
  const auto ra = profile_radii(sp, profile_a), rb = profile_radii(sp, profile_b);
  const double s2 = std::max(s1, std::min(ra.back().first, rb.back().first));
  auto radius = [&](double s) { return 0.5 * (interpolate(ra, s) + interpolate(rb, s)); };
  auto ring_points = [&](double r) { return std::max(8.0, std::ceil(2 * std::numbers::pi * r / d)); };
  // The rings' points before any ring: a cross-section or profile point far away (1e9) makes
  // a ring of 2 pi r / d points. The spine's resampling bounds the number of rings.
  double points = 0;
  for (double s = s1; s <= s2 + 1e-9; s += d) points += ring_points(s == s1 ? c1.radius : radius(s));
  points += annulus_radii(inner_ratio * c1.radius, outer_ratio * c1.radius, d) *
            annulus_ring_points(outer_ratio * c1.radius, d);
  if (!(points <= kMaxRingPoints))
    throw ResourceLimit("hair_sketch::Ponytail::constraints(): the cross sections need " + format_number(points) +
                        " points at grid spacing " + format_number(d) + ", at most " + format_number(kMaxRingPoints) +
                        " allowed (cross-section radius " + format_number(c1.radius) + ")");
  std::vector<Constraint> out;
  // 1. Longitudinal directions of the surface of revolution c(s) + r(s)(cos φ u + sin φ v):
  //    ∂/∂s = t + r'(s)(cos φ u + sin φ v), at the grid nodes nearest the cross sections.
  for (double s = s1; s <= s2 + 1e-9; s += d) {
    const double r = s == s1 ? c1.radius : radius(s);
    const double dr = (radius(std::min(s + 0.5 * d, s2)) - radius(std::max(s - 0.5 * d, s1))) / d;
    const Eigen::Vector3d t = sp.tangent(s), c = sp.at(s);
    Eigen::Vector3d u, v;
    detail::orthonormal_frame(t, u, v);
    const int n = static_cast<int>(ring_points(r));
    for (int k = 0; k < n; ++k) {
      const double phi = 2 * std::numbers::pi * k / n;
      const Eigen::Vector3d radial = std::cos(phi) * u + std::sin(phi) * v;
      detail::constrain_nearest(grid, c + r * radial, (t + dr * radial).normalized(), out);
    }
  }
  // 2. Spine tangents from C2 on, like a stream curve.
  for (double s = s2; s + d <= sp.length() + 1e-9; s += d)
    detail::constrain_cell(grid, sp.at(s + 0.5 * d), sp.tangent(s + 0.5 * d), out);
  // 3. Centripetal: nodes within half a spacing of C1's plane, radial distance in
  //    [1.3 r, 1.9 r], pointing at C1's centre with magnitude = tightness.
  const double r2 = outer_ratio * c1.radius, r1 = inner_ratio * c1.radius;
  const Eigen::Vector3d lo = grid.to_grid(c1.center - Eigen::Vector3d::Constant(r2 + d));
  const Eigen::Vector3d hi = grid.to_grid(c1.center + Eigen::Vector3d::Constant(r2 + d));
  for (int k = std::max(0, static_cast<int>(lo.z())); k <= std::min(grid.dims[2] - 1, static_cast<int>(hi.z()) + 1);
       ++k)
    for (int j = std::max(0, static_cast<int>(lo.y())); j <= std::min(grid.dims[1] - 1, static_cast<int>(hi.y()) + 1);
         ++j)
      for (int i = std::max(0, static_cast<int>(lo.x())); i <= std::min(grid.dims[0] - 1, static_cast<int>(hi.x()) + 1);
           ++i) {
        const int node = grid.index(i, j, k);
        const Eigen::Vector3d q = grid.position(node) - c1.center;
        const double h = q.dot(c1.normal);
        const double rho = (q - h * c1.normal).norm();
        if (std::abs(h) <= 0.5 * d && rho >= r1 && rho <= r2) out.push_back({node, -tightness * q.normalized()});
      }
  // An annulus thinner than a cell holds few nodes, with gaps between them that strands slip
  // through: the nodes nearest points of the annulus close the ring.
  centripetal_ring(grid, c1, r1, r2, tightness, out);
  return out;
}

}  // namespace lapis::hair_sketch
