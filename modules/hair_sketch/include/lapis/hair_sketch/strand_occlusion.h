// Self-shadowing of hair by its own density, for rendering. Deep opacity maps (Yuksel and
// Keyser 2008) slice the hair along a light's rays and accumulate opacity; this is the same
// quantity on a voxel grid: strands are splatted into a density grid (strand length per
// volume), and the optical depth toward a light is the density summed along the ray, so a
// strand under other hair is darker than one on the outside. The light is a soft sky: from
// above (+y, the head's up) and from the four horizontal axis directions, so the result does
// not depend on the camera and is computed once per regrowth, not per frame. Axis-aligned
// rays make every sum a prefix sum over the grid, O(cells), whatever the number of points.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "lapis/hair_sketch/growth.h"

namespace lapis::hair_sketch {

struct StrandOcclusionOptions {
  // Light falls to 1/e after this distance through hair of the strands' mean density (the mean
  // over occupied cells). Relative to the density, not per strand, so the look does not change
  // with the number of strands drawn. In the head's units (the bundled head is about 2 tall).
  double shadow_depth = 0.15;
  // Voxel size; 0: the longest side of the strands' bounding box over `cells_across`.
  double cell = 0;
  int cells_across = 64;
  // Share of the light from above; the rest comes equally from ±x and ±z. No light from below:
  // the head and body block it.
  double sky_weight = 0.5;
};

class StrandOcclusion {
 public:
  // Throws lapis::Error (naming the field) on a non-positive shadow_depth or cell, a
  // sky_weight outside [0, 1], or non-finite points.
  explicit StrandOcclusion(const Strands& strands, const StrandOcclusionOptions& options = {});

  // The light reaching p, in [0, 1]: 1 outside the hair, lower inside it.
  float transmittance(const Eigen::Vector3f& p) const;
  // Per point of `strands` (any strands, e.g. a decimated copy of the ones the grid was built from).
  std::vector<float> transmittance(const Strands& strands) const;

 private:
  Eigen::Vector3f origin_ = Eigen::Vector3f::Zero();  // the first cell's centre
  float inv_cell_ = 1;
  Eigen::Vector3i dims_ = Eigen::Vector3i::Zero();
  std::vector<float> light_;  // per cell: the weighted transmittance at its centre
};

}  // namespace lapis::hair_sketch
