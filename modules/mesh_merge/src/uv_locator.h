// Point location in a planar triangulation (a parameterization's uv and its faces): a uniform
// grid over the bounding box with about one face per cell, each face listed in the cells its
// box touches. The transition bands (§3.3.3) and the optimal boundary (§3.4) map points of one
// parameterization into the other's triangles with it.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "lapis/geometry/tri_mesh.h"

namespace lapis::mesh_merge::detail {

struct UvHit {
  int face = -1;                                      // -1: the triangulation has no face of positive area
  Eigen::Vector3d weights = Eigen::Vector3d::Zero();  // barycentric, as computed (may be < 0 outside)
  double min_weight = 0;                              // >= 0 inside the face (up to rounding)
};

class UvLocator {
 public:
  // Keeps references to uv and F.
  UvLocator(const Eigen::MatrixX2d& uv, const geometry::Faces& F);
  // The face whose barycentric coordinates of q have the largest minimum among the faces of q's
  // grid cell, or among all faces when none of those contains q (to within 1e-9), so points
  // just outside the triangulation find the nearest-looking face.
  UvHit locate(const Eigen::Vector2d& q) const;
  // Only the faces of q's grid cell, which hold every face that contains q: a point in none of
  // them gets the cell's best face with min_weight < 0 (or face -1 for an empty cell).
  UvHit locate_in_cell(const Eigen::Vector2d& q) const;

 private:
  bool barycentric(int f, const Eigen::Vector2d& q, Eigen::Vector3d& w) const;
  int cell(double x, int axis) const;
  const Eigen::MatrixX2d& uv_;
  const geometry::Faces& F_;
  Eigen::Vector2d lo_, size_;
  int g_ = 1;
  std::vector<std::vector<int>> cells_;
};

}  // namespace lapis::mesh_merge::detail
