// Hair growth along the field (thesis §4.6): from each root, append segments l·v(p) with
// l = 0.5 d and v the trilinearly interpolated field, until |v| < 0.05, the strand leaves
// the grid, or reaches its maximum length. Strands step in grid coordinates (q += 0.5 v(q),
// p = origin + d q), which saves a conversion per step. Strands grow in parallel (OpenMP) into a
// float field copy laid out node-major for cache-friendly lookups; the result does not
// depend on the thread count.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "lapis/hair_field/grid.h"
#include "lapis/hair_field/grid_operators.h"
#include "lapis/hair_sketch/head.h"

namespace lapis::hair_sketch {

// The field as growth reads it: float, x y z of a node contiguous.
class SampledField {
 public:
  SampledField(const hair_field::Grid& grid, const hair_field::Field& field);
  // Trilinear interpolation at a world point; zero outside the grid.
  Eigen::Vector3f operator()(const Eigen::Vector3f& p) const;
  // The same at grid coordinates q = (p − origin) / spacing, as growth steps them.
  Eigen::Vector3f at_grid(const Eigen::Vector3f& q) const;
  const hair_field::Grid& grid() const { return grid_; }
  const float* data() const { return data_.data(); }  // x y z per node, node-major

 private:
  hair_field::Grid grid_;
  std::vector<float> data_;  // 3 per node
};

struct GrowthOptions {
  double step = 0.5;            // segment length l in grid spacings d (thesis §4.6: l = 0.5d)
  double min_magnitude = 0.05;  // stop when |v(p)| < this (thesis §4.6)
  double max_length = 120;      // in grid spacings (the thesis stops only at the box; a cap
                                // keeps circulating flow from growing forever)
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
