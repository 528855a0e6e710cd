#include "lapis/hair_sketch/growth.h"

#include <algorithm>
#include <array>
#include <cmath>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace lapis::hair_sketch {

SampledField::SampledField(const Grid& grid, const Field& field)
    : grid_(grid),
      origin_(grid.origin.cast<float>()),
      inv_spacing_(static_cast<float>(1.0 / grid.spacing)),
      data_(field.data(), field.data() + field.size()) {
  // Padding: the vector lookup reads a node's x y z as four floats (trilinear_sse).
  data_.resize(data_.size() + 4, 0.0f);
}

namespace {

// Trilinear interpolation at grid coordinates q (in spacings from the origin), which must
// lie inside the grid: the cell's first corner and its fractions.
struct Cell {
  const float* e00;  // x y z of corner (i, j, k); (i+1, j, k) follows
  std::ptrdiff_t sy, sz;
  float fx, fy, fz;
};

inline Cell locate(const float* data, const std::array<int, 3>& dims, float qx, float qy,
                   float qz) {
  const int i = std::min(static_cast<int>(qx), dims[0] - 2);
  const int j = std::min(static_cast<int>(qy), dims[1] - 2);
  const int k = std::min(static_cast<int>(qz), dims[2] - 2);
  const std::ptrdiff_t sy = 3 * static_cast<std::ptrdiff_t>(dims[0]), sz = sy * dims[1];
  return {data + 3 * static_cast<std::ptrdiff_t>(i) + sy * j + sz * k, sy, sz, qx - i, qy - j,
          qz - k};
}

// The four x-edges of the cell, then lerps along x, y, z: a dependency chain three
// multiply-adds deep instead of a sum over the eight corners.
inline void trilinear(const Cell& c, float v[3]) {
  const float *e00 = c.e00, *e10 = e00 + c.sy, *e01 = e00 + c.sz, *e11 = e01 + c.sy;
  auto lerp = [](float a, float b, float t) { return a + t * (b - a); };
  for (int d = 0; d < 3; ++d) {
    const float c00 = lerp(e00[d], e00[3 + d], c.fx), c10 = lerp(e10[d], e10[3 + d], c.fx);
    const float c01 = lerp(e01[d], e01[3 + d], c.fx), c11 = lerp(e11[d], e11[3 + d], c.fx);
    v[d] = lerp(lerp(c00, c10, c.fy), lerp(c01, c11, c.fy), c.fz);
  }
}

#if defined(__SSE2__)
// The same lerps on x y z at once (lane 3 is ignored): an x-edge is six consecutive floats,
// read as two overlapping 4-float loads, so each lerp is one vector subtract, multiply and
// add. The operations and their order per component are those of trilinear(), so the
// result is bit for bit the same (the project's portable x86-64 build has no fused
// multiply-add for the compiler to contract either into; a -march=native build may).
inline void trilinear_sse(const Cell& c, float v[4]) {
  const __m128 fx = _mm_set1_ps(c.fx), fy = _mm_set1_ps(c.fy), fz = _mm_set1_ps(c.fz);
  auto lerp = [](__m128 a, __m128 b, __m128 t) { return _mm_add_ps(a, _mm_mul_ps(t, _mm_sub_ps(b, a))); };
  auto edge = [&](const float* e) { return lerp(_mm_loadu_ps(e), _mm_loadu_ps(e + 3), fx); };
  const __m128 c00 = edge(c.e00), c10 = edge(c.e00 + c.sy);
  const __m128 c01 = edge(c.e00 + c.sz), c11 = edge(c.e00 + c.sz + c.sy);
  _mm_storeu_ps(v, lerp(lerp(c00, c10, fy), lerp(c01, c11, fy), fz));
}
#endif

inline void field_at(const Cell& c, float v[4]) {
#if defined(__SSE2__)
  trilinear_sse(c, v);
#else
  trilinear(c, v);
#endif
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
    trilinear(locate(data_.data(), grid_.dims, q.x(), q.y(), q.z()), v.data());
  return v;
}

namespace {

// Strands growing side by side in one thread. A strand's steps form one dependency chain
// (position → cell → lookup → position), so a lone strand leaves the core waiting on
// latency; eight chains in turn keep it busy.
constexpr int kLanes = 8;

// Strands [first, last) grown into one block, kLanes at a time: each lane appends its points
// to its own buffer, and finished groups go to the block in strand order.
void grow_block(const SampledField& field, const std::vector<Eigen::Vector3d>& roots, int first,
                int last, float l, int max_steps, float vmin, std::vector<Eigen::Vector3f>& points,
                std::vector<int>& counts) {
  const float vmin2 = vmin * vmin;
  const std::array<int, 3>& dims = field.grid().dims;
  const float* data = field.data();
  const Eigen::Vector3f o = field.grid().origin.cast<float>();
  const float inv = static_cast<float>(1.0 / field.grid().spacing);
  std::array<std::vector<Eigen::Vector3f>, kLanes> lanes;
  const size_t typical = static_cast<size_t>(std::min(max_steps + 1, 256));
  for (auto& lane : lanes) lane.reserve(typical);  // once per block, not per growing strand
  points.clear();
  counts.clear();
  // Room for strands of the default maximum length (240 steps): the buffer then does not
  // move, and a regrowth with longer strands only touches new pages at its end (reserved but
  // untouched memory costs nothing). Capped, so that a huge maximum length reserves nothing
  // absurd.
  points.reserve(static_cast<size_t>(last - first) * typical);
  for (int s0 = first; s0 < last; s0 += kLanes) {
    const int m = std::min(kLanes, last - s0);
    unsigned growing = 0;
    for (int a = 0; a < m; ++a) {
      lanes[a].assign(1, roots[s0 + a].cast<float>());
      growing |= 1u << a;
    }
    for (int it = 0; it < max_steps && growing; ++it)
      for (int a = 0; a < m; ++a) {
        if (!(growing & (1u << a))) continue;
        const Eigen::Vector3f p = lanes[a].back();
        const float qx = (p[0] - o.x()) * inv, qy = (p[1] - o.y()) * inv;
        const float qz = (p[2] - o.z()) * inv;
        // Outside the grid the field is zero, so the strand stops at the box.
        const bool in = inside(dims, qx, qy, qz);
        float v[4];
        if (in) field_at(locate(data, dims, qx, qy, qz), v);
        if (!in || v[0] * v[0] + v[1] * v[1] + v[2] * v[2] < vmin2) {
          growing &= ~(1u << a);
          continue;
        }
        lanes[a].emplace_back(p[0] + l * v[0], p[1] + l * v[1], p[2] + l * v[2]);
      }
    for (int a = 0; a < m; ++a) {
      points.insert(points.end(), lanes[a].begin(), lanes[a].end());
      counts.push_back(static_cast<int>(lanes[a].size()));
    }
  }
}

}  // namespace

void StrandGrower::grow(const SampledField& field, const std::vector<Eigen::Vector3d>& roots,
                        Strands& out) {
  const int n = static_cast<int>(roots.size());
  const float l = static_cast<float>(options_.step * field.grid().spacing);
  const int max_steps = std::max(1, static_cast<int>(options_.max_length / options_.step));
  const float vmin = static_cast<float>(options_.min_magnitude);
  constexpr int kBlock = 64;
  const int blocks = (n + kBlock - 1) / kBlock;
  if (static_cast<int>(blocks_.size()) < blocks) blocks_.resize(blocks);
#pragma omp parallel for schedule(dynamic, 1)
  for (int b = 0; b < blocks; ++b)
    grow_block(field, roots, b * kBlock, std::min(n, (b + 1) * kBlock), l, max_steps, vmin,
               blocks_[b].points, blocks_[b].counts);
  // Blocks in strand order, so the result does not depend on which thread grew what.
  std::vector<size_t> block_start(blocks + 1, 0);
  for (int b = 0; b < blocks; ++b) block_start[b + 1] = block_start[b] + blocks_[b].points.size();
  // With headroom, so that strands growing a little longer on the next edit do not move the
  // whole buffer to fresh pages.
  if (block_start[blocks] > out.points.capacity()) out.points.reserve(block_start[blocks] * 3 / 2);
  out.points.resize(block_start[blocks]);
  out.offsets.assign(1, 0);
  out.offsets.reserve(n + 1);
  for (int b = 0; b < blocks; ++b)
    for (int c : blocks_[b].counts) out.offsets.push_back(out.offsets.back() + c);
#pragma omp parallel for schedule(static)
  for (int b = 0; b < blocks; ++b)
    std::copy(blocks_[b].points.begin(), blocks_[b].points.end(), out.points.begin() + block_start[b]);
}

Strands grow_strands(const SampledField& field, const std::vector<Eigen::Vector3d>& roots,
                     const GrowthOptions& options) {
  Strands out;
  StrandGrower(options).grow(field, roots, out);
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
