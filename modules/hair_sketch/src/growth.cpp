#include "lapis/hair_sketch/growth.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "lapis/core/error.h"
#include "lapis/core/format.h"

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace lapis::hair_sketch {
using hair_field::Field;
using hair_field::Grid;

SampledField::SampledField(const Grid& grid, const Field& field, const HeadClearance* head)
    : grid_(grid), head_(head), data_(4 * static_cast<std::size_t>(field.rows())) {
  constexpr const char* fn = "hair_sketch::SampledField";
  if (field.rows() != grid.num_nodes() || field.cols() != 3)
    throw InvalidArgument(std::string(fn) + ": the field has " + std::to_string(field.rows()) + " rows for " +
                          std::to_string(grid.num_nodes()) + " grid nodes");
  if (head &&
      !(head->grid().dims == grid.dims && head->grid().origin == grid.origin && head->grid().spacing == grid.spacing))
    throw InvalidArgument(std::string(fn) + ": the head's clearance is sampled on another grid");
  for (Eigen::Index i = 0; i < field.rows(); ++i) {
    float* node = &data_[4 * static_cast<std::size_t>(i)];
    for (int a = 0; a < 3; ++a) node[a] = static_cast<float>(field(i, a));
    node[3] = head ? head->node_distances()[i] : kFarFromHead;
  }
}

namespace {

// Four floats as one SIMD register (GCC/Clang vector extensions: SSE on x86-64, NEON on
// ARM, scalar code elsewhere). A position is x y z in lanes 0–2, in grid coordinates
// (spacings from the origin), so that a step needs no conversion from world coordinates.
typedef float Float4 __attribute__((vector_size(4 * sizeof(float))));
typedef int Int4 __attribute__((vector_size(4 * sizeof(int))));

inline Float4 load4(const float* p) {
  Float4 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

inline Float4 splat(float x) { return Float4{x, x, x, x}; }

// What a lookup needs of the field.
struct Lookup {
  const float* data;      // x y z and the head's distance per node, node-major (SampledField)
  std::ptrdiff_t sy, sz;  // float offsets of the next node along y and z
  Float4 far_corner;      // dims − 1
  Float4 last_cell;       // dims − 2: the first corner of the last cell per axis
};

Lookup lookup_of(const SampledField& field) {
  const std::array<int, 3>& d = field.grid().dims;
  const std::ptrdiff_t sy = 4 * static_cast<std::ptrdiff_t>(d[0]);
  return {field.data(), sy, sy * d[1], Float4{float(d[0] - 1), float(d[1] - 1), float(d[2] - 1), 0.f},
          Float4{float(d[0] - 2), float(d[1] - 2), float(d[2] - 2), 0.f}};
}

// Inside the grid, where the field is defined (a NaN position is not).
inline bool inside(const Lookup& f, Float4 q) {
  const Int4 in = (q >= Float4{}) & (q <= f.far_corner);
#if defined(__SSE2__)
  return (_mm_movemask_ps(reinterpret_cast<__m128>(in)) & 7) == 7;
#else
  return in[0] && in[1] && in[2];
#endif
}

// Trilinear interpolation at q, which must be inside the grid: the field in lanes 0–2, the
// head's coarse distance in lane 3. The cell's four x-edges, then lerps along x, y and z: a
// dependency chain three multiply-adds deep instead of a sum over the eight corners. An
// x-edge is two nodes of four floats, so each lerp is one vector subtract, multiply and add
// on all four lanes at once.
inline Float4 interpolate(const Lookup& f, Float4 q) {
  const Int4 cell = __builtin_convertvector(q < f.last_cell ? q : f.last_cell, Int4);
  const Float4 t = q - __builtin_convertvector(cell, Float4);
  const float* e00 = f.data + 4 * static_cast<std::ptrdiff_t>(cell[0]) + f.sy * cell[1] + f.sz * cell[2];
  const Float4 tx = splat(t[0]), ty = splat(t[1]), tz = splat(t[2]);
  auto lerp = [](Float4 a, Float4 b, Float4 w) { return a + w * (b - a); };
  auto edge = [&](const float* e) { return lerp(load4(e), load4(e + 4), tx); };
  return lerp(lerp(edge(e00), edge(e00 + f.sy), ty), lerp(edge(e00 + f.sz), edge(e00 + f.sz + f.sy), ty), tz);
}

inline Float4 to_grid(const SampledField& field, const Eigen::Vector3f& p) {
  const Eigen::Vector3f q = (p - field.grid().origin.cast<float>()) * static_cast<float>(1.0 / field.grid().spacing);
  return Float4{q.x(), q.y(), q.z(), 0.f};
}

}  // namespace

Eigen::Vector3f SampledField::operator()(const Eigen::Vector3f& p) const {
  const Float4 q = to_grid(*this, p);
  return at_grid({q[0], q[1], q[2]});
}

Eigen::Vector3f SampledField::at_grid(const Eigen::Vector3f& q) const {
  const Lookup f = lookup_of(*this);
  const Float4 g{q.x(), q.y(), q.z(), 0.f};
  if (!inside(f, g)) return Eigen::Vector3f::Zero();
  const Float4 v = interpolate(f, g);
  return {v[0], v[1], v[2]};
}

namespace {

// Strands growing side by side in one thread. A strand's steps form one dependency chain
// (position → cell → lookup → position), so a lone strand leaves the core waiting on
// latency; eight chains in turn keep it busy.
constexpr int kLanes = 8;

// Keeping a strand out of the head: where the coarse distance (lane 3 of a lookup) says the
// last point may be closer than `clearance`, the fine distance decides, and a point too close is
// pushed out.
struct Obstacle {
  const HeadClearance* head;  // null: no check
  float clearance;            // world units
  float near;                 // coarse distance below which the fine one is read
};

enum class Settled { Clear, Moved, Stuck };

// Moves the last point of `lane` (not its root) out of the head. Stuck when it could not move
// away from the point before it: the field points straight into the head, and the strand ends
// at that point (the pushed point is dropped). Where the scalp curves tighter than the segment
// (an ear, the nose), a segment between two clear points can still cut through it: then its
// midpoint is pushed out too and joins the strand.
Settled settle(const Obstacle& obstacle, std::vector<Eigen::Vector3f>& lane) {
  if (lane.size() < 2) return Settled::Clear;
  const HeadClearance& head = *obstacle.head;
  Eigen::Vector3f p = lane.back();
  const Eigen::Vector3f before = lane[lane.size() - 2];
  Settled result = Settled::Clear;
  double distance = head(p);
  if (distance < obstacle.clearance) {
    const Eigen::Vector3f out = head.push_out(p, obstacle.clearance);
    if ((out - before).squaredNorm() < 0.0025f * (p - before).squaredNorm()) {
      lane.pop_back();
      return Settled::Stuck;
    }
    p = lane.back() = out;
    distance = obstacle.clearance;
    result = Settled::Moved;
  }
  // The distance is 1-Lipschitz: farther than half the segment plus the clearance, the
  // midpoint is clear.
  if (distance >= obstacle.clearance + 0.5f * (p - before).norm()) return result;
  const Eigen::Vector3f mid = 0.5f * (before + p);
  if (head(mid) < obstacle.clearance) lane.insert(lane.end() - 1, head.push_out(mid, obstacle.clearance));
  return result;
}

// Strands [first, last) grown into one block, kLanes at a time: each lane appends its points
// to its own buffer, and finished groups go to the block in strand order.
// `step` is the segment length per unit of field in grid spacings.
void grow_block(const SampledField& field, const std::vector<Eigen::Vector3d>& roots, int first, int last, float step,
                int max_steps, float vmin, const Obstacle& obstacle, std::vector<Eigen::Vector3f>& points,
                std::vector<int>& counts) {
  const float vmin2 = vmin * vmin;
  const Lookup f = lookup_of(field);
  const Eigen::Vector3f origin = field.grid().origin.cast<float>();
  const Float4 o{origin.x(), origin.y(), origin.z(), 0.f};
  const Float4 d = splat(static_cast<float>(field.grid().spacing));
  const Float4 l{step, step, step, 0.f};  // lane 3 of a position stays 0
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
    Float4 q[kLanes];  // each lane's last point in grid coordinates
    for (int a = 0; a < m; ++a) {
      lanes[a].assign(1, roots[s0 + a].cast<float>());
      q[a] = to_grid(field, lanes[a][0]);
      growing |= 1u << a;
    }
    for (int it = 0; it < max_steps && growing; ++it)
      for (int a = 0; a < m; ++a) {
        if (!(growing & (1u << a))) continue;
        // Outside the grid the field is zero, so the strand stops at the box.
        if (!inside(f, q[a])) {
          growing &= ~(1u << a);
          continue;
        }
        Float4 v = interpolate(f, q[a]);
        if (v[3] < obstacle.near) {
          const Settled settled = settle(obstacle, lanes[a]);
          if (settled == Settled::Stuck) {
            growing &= ~(1u << a);
            continue;
          }
          if (settled == Settled::Moved) {  // else q stays as stepped, not rounded through p
            q[a] = to_grid(field, lanes[a].back());
            v = interpolate(f, q[a]);
          }
        }
        if (v[0] * v[0] + v[1] * v[1] + v[2] * v[2] < vmin2) {
          growing &= ~(1u << a);
          continue;
        }
        q[a] += l * v;
        const Float4 p = o + d * q[a];
        lanes[a].emplace_back(p[0], p[1], p[2]);
      }
    for (int a = 0; a < m; ++a) {
      // A strand stopped by its step count has a last point no lookup has checked.
      if (obstacle.head && (growing & (1u << a))) settle(obstacle, lanes[a]);
      points.insert(points.end(), lanes[a].begin(), lanes[a].end());
      counts.push_back(static_cast<int>(lanes[a].size()));
    }
  }
}

}  // namespace

namespace {
// At least one step (a zero length grows one segment, as sessions allow).
double max_steps_of(const GrowthOptions& o) { return std::max(1.0, std::floor(o.max_length / o.step)); }
}  // namespace

double estimate_strand_bytes(double roots, const GrowthOptions& o) {
  // Per point: the growth buffer and the result with 1.5x headroom; per root: its position,
  // its offset and its block count.
  const double points = roots * (max_steps_of(o) + 1);
  return points * 2.5 * sizeof(Eigen::Vector3f) + roots * (sizeof(Eigen::Vector3d) + 2 * sizeof(int));
}

void check_growth(double roots, const GrowthOptions& o, const std::string& fn) {
  if (!(std::isfinite(o.step) && o.step > 0))
    throw InvalidArgument(fn + ": step must be positive, got " + format_number(o.step));
  if (!(std::isfinite(o.max_length) && o.max_length >= 0))
    throw InvalidArgument(fn + ": max_length must be non-negative, got " + format_number(o.max_length));
  if (!(std::isfinite(o.min_magnitude) && o.min_magnitude >= 0))
    throw InvalidArgument(fn + ": min_magnitude must be non-negative, got " + format_number(o.min_magnitude));
  if (!(std::isfinite(o.head_clearance) && o.head_clearance >= 0 && o.head_clearance <= 1))
    throw InvalidArgument(fn + ": head_clearance must be in [0, 1] grid spacings, got " +
                          format_number(o.head_clearance));
  if (!(roots >= 0 && roots <= std::numeric_limits<int>::max() / 2))
    throw InvalidArgument(fn + ": " + format_number(roots) + " roots are too many");
  const double points = roots * (max_steps_of(o) + 1), bytes = estimate_strand_bytes(roots, o);
  const std::string what = fn + ": " + format_number(roots) + " strands of up to " + format_number(max_steps_of(o)) +
                           " steps (max_length " + format_number(o.max_length) + " / step " + format_number(o.step) +
                           ")";
  if (points > std::numeric_limits<int>::max())
    throw ResourceLimit(what + " may have " + format_number(points) + " points, more than the " +
                        std::to_string(std::numeric_limits<int>::max()) + " strands can index");
  if (bytes > o.memory_limit_bytes)
    throw ResourceLimit(what + " may need " + format_number(bytes / (1 << 20)) + " MiB, more than the limit of " +
                        format_number(o.memory_limit_bytes / (1 << 20)) + " MiB");
}

void StrandGrower::grow(const SampledField& field, const std::vector<Eigen::Vector3d>& roots, Strands& out) {
  constexpr const char* fn = "hair_sketch::StrandGrower::grow()";
  const GrowthOptions& o = options_;
  check_growth(static_cast<double>(roots.size()), o, fn);
  for (size_t i = 0; i < roots.size(); ++i)
    if (!roots[i].allFinite())
      throw InvalidArgument(std::string(fn) + ": root " + std::to_string(i) + " is not finite");
  const int n = static_cast<int>(roots.size());
  const float l = static_cast<float>(o.step);
  const int max_steps = static_cast<int>(max_steps_of(o));  // check_growth keeps it in int range
  const float vmin = static_cast<float>(o.min_magnitude);
  Obstacle obstacle{nullptr, 0.f, -std::numeric_limits<float>::infinity()};
  if (o.keep_outside_head && field.head()) {
    const double spacing = field.grid().spacing;
    // The coarse distance interpolates exact distances at a cell's corners, and the distance is
    // 1-Lipschitz: it is off by at most the distance to the corners, half a cell diagonal. Closer
    // than that to the clearance, the fine samples decide. (A segment whose end lies beyond that
    // band has its midpoint checked only by the band too. Its chord sags below its ends by
    // l²/8R; to reach into the head it would need both a surface curved tighter than 0.6 d and
    // a coarse distance that much off there. No bundled session or test shows one.)
    obstacle.head = field.head();
    obstacle.clearance = static_cast<float>(o.head_clearance * spacing);
    obstacle.near = static_cast<float>((o.head_clearance + std::sqrt(3.0) / 2 + 1e-3) * spacing);
  }
  constexpr int kBlock = 64;
  const int blocks = (n + kBlock - 1) / kBlock;
  if (static_cast<int>(blocks_.size()) < blocks) blocks_.resize(blocks);
#pragma omp parallel for schedule(dynamic, 1)
  for (int b = 0; b < blocks; ++b)
    grow_block(field, roots, b * kBlock, std::min(n, (b + 1) * kBlock), l, max_steps, vmin, obstacle, blocks_[b].points,
               blocks_[b].counts);
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
