// The head's signed distance (negative inside), read by trilinear interpolation: the cheap
// test that keeps grown strands and detail offsets out of the head. Two levels: the field's
// grid everywhere, and, in the grid cells the surface passes near, a block of finer samples
// (a curl's radius is a fraction of the grid spacing, so the coarse samples alone blur the
// scalp by more than that).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "lapis/hair_field/grid.h"
#include "lapis/hair_sketch/head.h"

namespace lapis::hair_sketch {

class HeadClearance {
 public:
  static constexpr int kRefinement = 4;  // fine samples per coarse cell and axis
  HeadClearance(const Head& head, const hair_field::Grid& grid);
  double operator()(const Eigen::Vector3f& p) const;  // +spacing outside the grid
  // The same at grid coordinates q = (p − origin) / spacing, as growth steps them.
  // `gradient`, if given, receives the interpolant's gradient per grid spacing.
  float at_grid(const Eigen::Vector3f& q, Eigen::Vector3f* gradient = nullptr) const;
  // p moved along the distance's gradient until it is at least `clearance` outside (a few
  // Newton steps on the sampled distance, at_grid's); p itself where it already is.
  Eigen::Vector3f push_out(const Eigen::Vector3f& p, float clearance) const;

  const hair_field::Grid& grid() const { return grid_; }
  const std::vector<float>& node_distances() const { return distance_; }  // the coarse samples
  int refined_cells() const { return static_cast<int>(blocks_.size() / kBlockSize); }

 private:
  static constexpr int kBlockSize = (kRefinement + 1) * (kRefinement + 1) * (kRefinement + 1);
  // The signed distance at a point of the fine lattice (kRefinement points per spacing).
  double fine_sample(const Head& head, const Eigen::Vector3i& fine) const;
  hair_field::Grid grid_;
  std::vector<float> distance_;     // per node
  std::vector<int> block_of_cell_;  // per cell (indexed like its lowest node), -1: not refined
  std::vector<float> blocks_;       // kBlockSize samples per refined cell
};

}  // namespace lapis::hair_sketch
