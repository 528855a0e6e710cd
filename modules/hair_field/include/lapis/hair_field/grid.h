// The uniform 3D grid that carries the hair vector field (thesis §4.3, §4.6): it covers the
// head's bounding box enlarged to leave room for long hair, with a resolution derived from
// a target number of unknowns, and it estimates its memory before anything is allocated.
#pragma once

#include <array>
#include <cstdint>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace lapis::hair_field {

// Node (i, j, k) sits at origin + spacing * (i, j, k); index = i + dims[0] * (j + dims[1] * k).
struct Grid {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  double spacing = 1.0;              // d, the thesis' "step size in the vector field"
  std::array<int, 3> dims{1, 1, 1};  // nodes per axis

  std::int64_t num_nodes() const { return static_cast<std::int64_t>(dims[0]) * dims[1] * dims[2]; }
  int index(int i, int j, int k) const { return i + dims[0] * (j + dims[1] * k); }
  std::array<int, 3> coords(int node) const {
    return {node % dims[0], (node / dims[0]) % dims[1], node / (dims[0] * dims[1])};
  }
  Eigen::Vector3d position(int node) const {
    const auto c = coords(node);
    return origin + spacing * Eigen::Vector3d(c[0], c[1], c[2]);
  }
  Eigen::Vector3d max_corner() const {
    return origin + spacing * Eigen::Vector3d(dims[0] - 1, dims[1] - 1, dims[2] - 1);
  }
  bool contains(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d q = (p - origin) / spacing;
    return q.x() >= 0 && q.y() >= 0 && q.z() >= 0 && q.x() <= dims[0] - 1 && q.y() <= dims[1] - 1 &&
           q.z() <= dims[2] - 1;
  }
  // Grid coordinates of p (continuous; node (i,j,k) at integer values).
  Eigen::Vector3d to_grid(const Eigen::Vector3d& p) const { return (p - origin) / spacing; }
};

// What the field may allocate by default (bytes): GridOptions and FieldSolverOptions start
// from it.
inline constexpr double kDefaultMemoryLimitBytes = 16.0 * (1ull << 30);

struct GridOptions {
  // Unknowns per field component. Thesis §4.6: "about 25K" for smooth styles, "about 50K"
  // for complex ones such as ponytails; the interactive targets go up to 1M.
  double target_unknowns = 25000;
  // Enlargement of the head box, in head-box extents. The thesis only says "bounding
  // volume"; hair below the shoulders needs room under the head (y is up).
  double margin_side = 0.3;   // each of ±x, ±z
  double margin_top = 0.15;   // +y
  double margin_below = 1.0;  // -y: long hair
  // Memory the field may use (bytes); make_grid throws ResourceLimit beyond it.
  double memory_limit_bytes = kDefaultMemoryLimitBytes;
};

// Bytes the fast (multigrid) field path needs for n nodes: fine and coarse operators in
// float with indices, the double field and the CG work vectors (the measured layout, see
// grid.cpp).
double estimate_multigrid_bytes(std::int64_t n);
// Bytes of the thesis path's simplicial LDLᵀ factor for n nodes. The 3D bi-Laplacian fills
// in like n^(4/3); the constant is fitted to the measured 38M non-zeros at 50K unknowns,
// 12 bytes per non-zero (value + row index).
double estimate_cholesky_bytes(std::int64_t n);

// The grid over head_box enlarged by the options' margins with about target_unknowns nodes.
// Throws InvalidArgument for an empty/non-finite box or target < 8, ResourceLimit when even
// the fast path would exceed memory_limit_bytes.
Grid make_grid(const Eigen::AlignedBox3d& head_box, const GridOptions& options = {});

}  // namespace lapis::hair_field
