// Private: the interpolation of the isolines' transformations to the vertices (Au et al. 2007,
// §4.2). Per vertex and isoline set i, the two isolines j, j + 1 whose isovalues bracket
// φ_i(k) and the weights φ_i(k)(1 − α), φ_i(k) α, so that row k of W_x is
// Σ_i [φ_i(1−α) e_{i,j} + φ_i α e_{i,j+1}] ⊗ [x̄_k 1] and of W_δ the same ⊗ δ̄_k (§4.3). The
// matrices are never stored: 2K (isoline, weight) pairs per vertex are (K · 20 bytes a vertex).
// Positions are normalized (centre at the origin, bounding-box diagonal 1) so that the soft
// weights ω, β mean the same on every mesh.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "lapis/geometry/tri_mesh.h"
#include "lapis/solver/types.h"

namespace lapis::mesh_deform::detail {

// R (4m by 3, block ℓ = r_ℓᵀ) as contiguous 4×3 blocks: the per-vertex blends read one block
// per bracket instead of three strided columns of R.
using TransformBlock = Eigen::Matrix<double, 4, 3>;
using TransformBlocks = std::vector<TransformBlock, Eigen::aligned_allocator<TransformBlock>>;
TransformBlocks transform_blocks(const solver::DenseMatrix& R);

// Σ_i [w0_i h R_{lower_i} + w1_i h R_{lower_i + 1}] over the K brackets of one vertex.
inline Eigen::Vector3d blend(const Eigen::Vector4d& h, const int* lower, const double* w0, const double* w1, int sets,
                             const TransformBlocks& R) {
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (int i = 0; i < sets; ++i) x.noalias() += (w0[i] * R[lower[i]] + w1[i] * R[lower[i] + 1]).transpose() * h;
  return x;
}

struct IsolineBasis {
  int sets = 0;      // K: one per handle, one in all when there are two handles (§4.1)
  int isolines = 0;  // N per set
  int vertices = 0;
  std::vector<int> lower;           // #V·K: global isoline index i·N + j of the lower bracket
  std::vector<double> w0, w1;       // #V·K: weights of isolines lower and lower + 1
  Eigen::Vector3d center{0, 0, 0};  // of the bounding box
  double scale = 1;                 // bounding-box diagonal
  geometry::Vertices rest;          // #V by 3, normalized

  int count() const { return sets * isolines; }  // m
  int slot(int k, int i) const { return k * sets + i; }
  double isovalue(int j) const { return static_cast<double>(j) / (isolines - 1); }
  Eigen::Vector3d normalized(const Eigen::Vector3d& x) const { return (x - center) / scale; }
  Eigen::Vector3d denormalized(const Eigen::Vector3d& x) const { return center + scale * x; }

  Eigen::Vector4d homogeneous(int k) const { return {rest(k, 0), rest(k, 1), rest(k, 2), 1.0}; }
  // Row k of W_x times R: the vertex's position, normalized.
  Eigen::Vector3d position(int k, const TransformBlocks& R) const;
};

// The isolines of set i bracketing field value f (§4.2: s_j ≤ f ≤ s_{j+1}, α = (f − s_j) /
// (s_{j+1} − s_j)) and their weights, the set's share `weight` split (1 − α) : α.
struct IsolineBracket {
  int lower = 0;  // global index i·N + j
  double w0 = 0, w1 = 0;
};
IsolineBracket isoline_bracket(double f, double weight, int set, int isolines);

// Field column of isoline set i: the handle's own, or column 1 when one set serves two handles.
inline int field_of_set(int sets, int i) { return sets == 1 ? 1 : i; }

// phi  #V by H handle fields (rows sum to 1). One set per column, or one set for H = 2.
IsolineBasis make_isoline_basis(const geometry::Vertices& rest, const Eigen::MatrixXd& phi, int isolines);

}  // namespace lapis::mesh_deform::detail
