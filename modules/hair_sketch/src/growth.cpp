#include "lapis/hair_sketch/growth.h"

#include <algorithm>
#include <cmath>

namespace lapis::hair_sketch {

SampledField::SampledField(const Grid& grid, const Field& field)
    : grid_(grid),
      origin_(grid.origin.cast<float>()),
      inv_spacing_(static_cast<float>(1.0 / grid.spacing)),
      data_(field.data(), field.data() + field.size()) {}

Eigen::Vector3f SampledField::operator()(const Eigen::Vector3f& p) const {
  const Eigen::Vector3f q = (p - origin_) * inv_spacing_;
  const int nx = grid_.dims[0], ny = grid_.dims[1], nz = grid_.dims[2];
  if (!(q.x() >= 0 && q.y() >= 0 && q.z() >= 0 && q.x() <= nx - 1 && q.y() <= ny - 1 &&
        q.z() <= nz - 1))
    return Eigen::Vector3f::Zero();
  const int i = std::min(static_cast<int>(q.x()), nx - 2);
  const int j = std::min(static_cast<int>(q.y()), ny - 2);
  const int k = std::min(static_cast<int>(q.z()), nz - 2);
  const float fx = q.x() - i, fy = q.y() - j, fz = q.z() - k;
  const std::ptrdiff_t sy = nx, sz = static_cast<std::ptrdiff_t>(nx) * ny;
  const float* b = data_.data() + 3 * (i + sy * j + sz * k);
  Eigen::Vector3f r = Eigen::Vector3f::Zero();
  for (int c = 0; c < 8; ++c) {
    const int dx = c & 1, dy = (c >> 1) & 1, dz = c >> 2;
    const float w = (dx ? fx : 1 - fx) * (dy ? fy : 1 - fy) * (dz ? fz : 1 - fz);
    const float* v = b + 3 * (dx + sy * dy + sz * dz);
    r += w * Eigen::Vector3f(v[0], v[1], v[2]);
  }
  return r;
}

namespace {

// Strands grown by one task: their points back to back and each strand's point count.
struct StrandBlock {
  std::vector<Eigen::Vector3f> points;
  std::vector<int> counts;
};

// Strands [first, last) grown into one block. One growing buffer per block instead of one
// per strand: a strand's push_backs reallocate a dozen times, a block's a few.
void grow_block(const SampledField& field, const std::vector<Eigen::Vector3d>& roots, int first,
                int last, float l, int max_steps, float vmin, StrandBlock& out) {
  out.points.reserve(static_cast<size_t>(last - first) * 64);
  out.counts.reserve(last - first);
  for (int s = first; s < last; ++s) {
    const size_t start = out.points.size();
    Eigen::Vector3f p = roots[s].cast<float>();
    out.points.push_back(p);
    for (int it = 0; it < max_steps; ++it) {
      const Eigen::Vector3f v = field(p);
      // Outside the grid the lookup is zero, so this also stops at the box.
      if (v.norm() < vmin) break;
      p += l * v;
      out.points.push_back(p);
    }
    out.counts.push_back(static_cast<int>(out.points.size() - start));
  }
}

}  // namespace

Strands grow_strands(const SampledField& field, const std::vector<Eigen::Vector3d>& roots,
                     const GrowthOptions& options) {
  const int n = static_cast<int>(roots.size());
  const float l = static_cast<float>(options.step * field.grid().spacing);
  const int max_steps = std::max(1, static_cast<int>(options.max_length / options.step));
  const float vmin = static_cast<float>(options.min_magnitude);
  constexpr int kBlock = 64;
  const int blocks = (n + kBlock - 1) / kBlock;
  std::vector<StrandBlock> grown(blocks);
#pragma omp parallel for schedule(dynamic, 1)
  for (int b = 0; b < blocks; ++b)
    grow_block(field, roots, b * kBlock, std::min(n, (b + 1) * kBlock), l, max_steps, vmin,
               grown[b]);
  // Blocks in strand order, so the result does not depend on which thread grew what.
  std::vector<size_t> block_start(blocks + 1, 0);
  for (int b = 0; b < blocks; ++b) block_start[b + 1] = block_start[b] + grown[b].points.size();
  Strands out;
  out.points.resize(block_start[blocks]);
  out.offsets.reserve(n + 1);
  for (const StrandBlock& g : grown)
    for (int c : g.counts) out.offsets.push_back(out.offsets.back() + c);
#pragma omp parallel for schedule(static)
  for (int b = 0; b < blocks; ++b)
    std::copy(grown[b].points.begin(), grown[b].points.end(), out.points.begin() + block_start[b]);
  return out;
}

int count_penetrating_segments(const Strands& strands, const Head& head) {
  int count = 0;
  // Roots are outside, so a strand's side changes only where a segment crosses the
  // surface: one ray cast per segment, and an inside test only after a crossing (a grazing
  // segment may cross twice).
#pragma omp parallel for schedule(dynamic, 64) reduction(+ : count)
  for (int s = 0; s < strands.count(); ++s) {
    bool inside = false;
    for (int i = strands.offsets[s]; i + 1 < strands.offsets[s + 1]; ++i) {
      const Eigen::Vector3d a = strands.points[i].cast<double>();
      const Eigen::Vector3d b = strands.points[i + 1].cast<double>();
      const bool crosses = head.bvh->intersect(a, b - a, 1.0).has_value();
      if (crosses) inside = head.inside(b);
      if (crosses || inside) ++count;
    }
  }
  return count;
}

}  // namespace lapis::hair_sketch
