#include "lapis/hair_sketch/growth.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace lapis::hair_sketch {

SampledField::SampledField(const Grid& grid, const Field& field)
    : grid_(grid),
      origin_(grid.origin.cast<float>()),
      inv_spacing_(static_cast<float>(1.0 / grid.spacing)),
      data_(field.data(), field.data() + field.size()) {}

namespace {

// Trilinear interpolation at grid coordinates q (in spacings from the origin), which must
// lie inside the grid. The four x-edges of the cell, then lerps along x, y, z: a dependency
// chain three multiply-adds deep instead of a sum over the eight corners. Growth is a chain
// of dependent lookups, so that chain's latency is what a step costs.
inline void trilinear(const float* data, const std::array<int, 3>& dims, float qx, float qy,
                      float qz, float v[3]) {
  const int i = std::min(static_cast<int>(qx), dims[0] - 2);
  const int j = std::min(static_cast<int>(qy), dims[1] - 2);
  const int k = std::min(static_cast<int>(qz), dims[2] - 2);
  const float fx = qx - i, fy = qy - j, fz = qz - k;
  const std::ptrdiff_t sy = 3 * static_cast<std::ptrdiff_t>(dims[0]), sz = sy * dims[1];
  const float* e00 = data + 3 * static_cast<std::ptrdiff_t>(i) + sy * j + sz * k;
  const float* e10 = e00 + sy;
  const float* e01 = e00 + sz;
  const float* e11 = e01 + sy;
  auto lerp = [](float a, float b, float t) { return a + t * (b - a); };
  for (int c = 0; c < 3; ++c) {
    const float c00 = lerp(e00[c], e00[3 + c], fx), c10 = lerp(e10[c], e10[3 + c], fx);
    const float c01 = lerp(e01[c], e01[3 + c], fx), c11 = lerp(e11[c], e11[3 + c], fx);
    v[c] = lerp(lerp(c00, c10, fy), lerp(c01, c11, fy), fz);
  }
}

inline bool inside(const std::array<int, 3>& dims, float qx, float qy, float qz) {
  return qx >= 0 && qy >= 0 && qz >= 0 && qx <= dims[0] - 1 && qy <= dims[1] - 1 &&
         qz <= dims[2] - 1;
}

}  // namespace

Eigen::Vector3f SampledField::operator()(const Eigen::Vector3f& p) const {
  const Eigen::Vector3f q = (p - origin_) * inv_spacing_;
  Eigen::Vector3f v = Eigen::Vector3f::Zero();
  if (inside(grid_.dims, q.x(), q.y(), q.z()))
    trilinear(data_.data(), grid_.dims, q.x(), q.y(), q.z(), v.data());
  return v;
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
  const float vmin2 = vmin * vmin;
  const std::array<int, 3>& dims = field.grid().dims;
  const float* data = field.data();
  const Eigen::Vector3f o = field.grid().origin.cast<float>();
  const float inv = static_cast<float>(1.0 / field.grid().spacing);
  out.points.reserve(static_cast<size_t>(last - first) * 64);
  out.counts.reserve(last - first);
  for (int s = first; s < last; ++s) {
    const size_t start = out.points.size();
    float p[3] = {static_cast<float>(roots[s].x()), static_cast<float>(roots[s].y()),
                  static_cast<float>(roots[s].z())};
    out.points.emplace_back(p[0], p[1], p[2]);
    for (int it = 0; it < max_steps; ++it) {
      const float qx = (p[0] - o.x()) * inv, qy = (p[1] - o.y()) * inv;
      const float qz = (p[2] - o.z()) * inv;
      // Outside the grid the field is zero, so the strand stops at the box.
      if (!inside(dims, qx, qy, qz)) break;
      float v[3];
      trilinear(data, dims, qx, qy, qz, v);
      if (v[0] * v[0] + v[1] * v[1] + v[2] * v[2] < vmin2) break;
      for (int c = 0; c < 3; ++c) p[c] += l * v[c];
      out.points.emplace_back(p[0], p[1], p[2]);
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
