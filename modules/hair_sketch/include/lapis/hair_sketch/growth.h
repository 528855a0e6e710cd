// Hair growth along the field (thesis §4.6): from each root, append segments l·v(p) with
// l = 0.5 d and v the trilinearly interpolated field, until |v| < 0.05, the strand leaves
// the grid, or reaches its maximum length. Given the head's clearance, growth also keeps the
// strands out of the head (not in the thesis, see GrowthOptions::keep_outside_head). Strands step in grid coordinates
// (q += 0.5 v(q), p = origin + d q), which saves a conversion per step. Strands grow in parallel (OpenMP) into a float
// field copy laid out node-major for cache-friendly lookups; the result does not depend on the thread count.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "lapis/hair_field/grid.h"
#include "lapis/hair_field/grid_operators.h"
#include "lapis/hair_sketch/head.h"
#include "lapis/hair_sketch/head_clearance.h"

namespace lapis::hair_sketch {

// The field as growth reads it: float, x y z of a node contiguous, and beside them the head's
// coarse distance when growth is to keep the strands out of the head.
class SampledField {
 public:
  // `head`: the head's clearance on the same grid, or null (strands may then enter the head).
  // It must outlive this.
  SampledField(const hair_field::Grid& grid, const hair_field::Field& field, const HeadClearance* head = nullptr);
  // Trilinear interpolation at a world point; zero outside the grid.
  Eigen::Vector3f operator()(const Eigen::Vector3f& p) const;
  // The same at grid coordinates q = (p − origin) / spacing, as growth steps them.
  Eigen::Vector3f at_grid(const Eigen::Vector3f& q) const;
  const hair_field::Grid& grid() const { return grid_; }
  const HeadClearance* head() const { return head_; }
  const float* data() const { return data_.data(); }  // x y z distance per node, node-major

 private:
  static constexpr float kFarFromHead = 1e30f;  // the distance stored without a head
  hair_field::Grid grid_;
  const HeadClearance* head_;
  std::vector<float> data_;  // 4 per node
};

struct GrowthOptions {
  double step = 0.5;            // segment length l in grid spacings d (thesis §4.6: l = 0.5d)
  double min_magnitude = 0.05;  // stop when |v(p)| < this (thesis §4.6)
  double max_length = 120;      // in grid spacings (the thesis stops only at the box; a cap
                                // keeps circulating flow from growing forever)
  // Not in the thesis: §4.6's avoidance constraints act on grid nodes only, and between them
  // the interpolated field still points into the head near concave parts of the scalp, where
  // about 15% of the strands entered it close to their roots. With this on, a point that growth
  // would put inside the head (or closer than `head_clearance` grid spacings) is moved out along
  // the distance's gradient, so the strand slides along the scalp; a strand that cannot slide
  // (the field points straight in) stops. Off reproduces the thesis' strands.
  bool keep_outside_head = true;
  double head_clearance = 0.05;  // in grid spacings: above the chord error of a 0.5 d segment
  // Memory the strands may use (bytes): growth is refused, before it starts, when the worst
  // case (every strand max_length / step steps long) would need more.
  double memory_limit_bytes = 4.0 * (1ull << 30);
};

// Worst-case bytes of growing `roots` strands with these options: roots, points (the growth
// buffers and the result with its headroom) and offsets.
double estimate_strand_bytes(double roots, const GrowthOptions& options);

// Throws InvalidArgument (naming fn) for options out of their domain, ResourceLimit with the
// estimate when estimate_strand_bytes exceeds options.memory_limit_bytes or the points would
// not fit int offsets. Growth calls it; callers call it before costlier work that precedes it.
void check_growth(double roots, const GrowthOptions& options, const std::string& fn);

// Polylines: strand s has points [offsets[s], offsets[s+1]).
struct Strands {
  std::vector<Eigen::Vector3f> points;
  std::vector<int> offsets{0};
  int count() const { return static_cast<int>(offsets.size()) - 1; }
  int segments() const { return static_cast<int>(points.size()) - count(); }
};

// One strand from each root.
Strands grow_strands(const SampledField& field, const std::vector<Eigen::Vector3d>& roots,
                     const GrowthOptions& options = {});

// Growth for the interactive loop, where the strands regrow after every edit: it writes into
// memory that the previous regrowth touched (its own per-block buffers and the caller's
// strands), because a fresh allocation pays a page fault per 4 KB on first touch, which can
// cost as much as the growth itself. Keeps about one set of strands' worth of buffers.
class StrandGrower {
 public:
  explicit StrandGrower(GrowthOptions options = {}) : options_(options) {}

  // One strand from each root into `out`, whose storage is reused; the same strands as
  // grow_strands().
  void grow(const SampledField& field, const std::vector<Eigen::Vector3d>& roots, Strands& out);

  const GrowthOptions& options() const { return options_; }
  void set_options(const GrowthOptions& options) { options_ = options; }

 private:
  // Strands grown by one task: their points back to back and each strand's point count.
  struct Block {
    std::vector<Eigen::Vector3f> points;
    std::vector<int> counts;
  };
  GrowthOptions options_;
  std::vector<Block> blocks_;
};

// Segments that cross the head surface or lie inside it (one BVH ray cast per segment,
// crossing parity from the outside root), in parallel.
int count_penetrating_segments(const Strands& strands, const Head& head);

}  // namespace lapis::hair_sketch
