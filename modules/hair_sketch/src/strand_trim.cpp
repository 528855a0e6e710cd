// Length variation and the sketched cut line: details that shorten strands.
#include <array>
#include <limits>
#include <optional>

#include "strand_detail_ops.h"

namespace lapis::hair_sketch::detail {

Polyline vary_length(const LengthDetail& d, std::uint32_t seed, int index, const Polyline& p) {
  const std::vector<float> arc = arc_lengths(p);
  StrandRandom random(seed, index, 3);
  const double keep = random.uniform(1 - d.variation, 1);
  return truncate(p, arc, static_cast<float>(keep * arc.back()));
}

namespace {

// Pixel position of a world point, or nothing behind the camera.
std::optional<Eigen::Vector2d> to_screen(const geometry::CameraMatrices& camera, const Eigen::Matrix4d& view_projection,
                                         const Eigen::Vector3f& p) {
  const Eigen::Vector4d clip = view_projection * p.cast<double>().homogeneous();
  if (!(clip.w() > 1e-12)) return std::nullopt;
  const Eigen::Vector2d ndc = clip.head<2>() / clip.w();
  const auto& vp = camera.viewport;
  return Eigen::Vector2d(vp[0] + (ndc.x() + 1) * 0.5 * vp[2], vp[1] + (1 - ndc.y()) * 0.5 * vp[3]);
}

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// Parameter along a→b where it crosses c→d, if it does.
std::optional<double> crossing(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                               const Eigen::Vector2d& d) {
  const Eigen::Vector2d r = b - a, s = d - c;
  const double denom = cross(r, s);
  if (std::abs(denom) < 1e-300) return std::nullopt;  // parallel: no single crossing point
  const double t = cross(c - a, s) / denom, u = cross(c - a, r) / denom;
  if (t < 0 || t > 1 || u < 0 || u > 1) return std::nullopt;
  return t;
}

}  // namespace

Polyline cut_strand(const CutDetail& d, const Polyline& p) {
  const Eigen::Matrix4d view_projection = d.camera.projection * d.camera.view;
  Eigen::AlignedBox2d line_box;
  for (const auto& q : d.line) line_box.extend(q);
  const std::vector<float> arc = arc_lengths(p);
  std::optional<Eigen::Vector2d> previous = to_screen(d.camera, view_projection, p[0]);
  for (std::size_t i = 1; i < p.size(); ++i) {
    const std::optional<Eigen::Vector2d> current = to_screen(d.camera, view_projection, p[i]);
    if (previous && current) {
      Eigen::AlignedBox2d segment_box(previous->cwiseMin(*current), previous->cwiseMax(*current));
      if (segment_box.intersects(line_box)) {
        double first = std::numeric_limits<double>::infinity();
        for (std::size_t k = 1; k < d.line.size(); ++k)
          if (const auto t = crossing(*previous, *current, d.line[k - 1], d.line[k])) first = std::min(first, *t);
        if (first <= 1) return truncate(p, arc, arc[i - 1] + static_cast<float>(first) * (arc[i] - arc[i - 1]));
      }
    }
    previous = current;
  }
  return p;
}

}  // namespace lapis::hair_sketch::detail
