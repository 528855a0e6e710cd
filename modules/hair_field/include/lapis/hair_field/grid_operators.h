// The field energy's operators on the uniform grid (thesis §4.4.1, Eq. 4.1–4.3): the
// 6-neighbour Laplacian Δ(t_i) = Σ_{j∈N(i)} (t_j − t_i) / |N(i)| as a matrix D, the normal
// matrix DᵀD + WᵀW, and the same operator applied matrix-free (what iterative solvers use).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "lapis/hair_field/grid.h"

namespace lapis::hair_field {

// One direction vector per grid node, n by 3 (x, y, z solved together, §4.4.1).
using Field = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

// D  n by n: D(i,i) = −1, D(i,j) = 1/|N(i)| for the (up to 6) grid neighbours j of i.
SparseMatrix laplacian_matrix(const Grid& grid);

// DᵀD + diag(weights)  n by n, weights n (ω² at constrained nodes, 0 elsewhere: WᵀW).
SparseMatrix normal_matrix(const Grid& grid, const Eigen::VectorXd& weights);

// Y = (DᵀD + diag(weights)) X without forming the matrix: two 7-point passes, OpenMP over
// z-slabs. X, Y  n by 3; Y is resized.
void apply_normal_operator(const Grid& grid, const Eigen::VectorXd& weights, const Field& X, Field& Y);

}  // namespace lapis::hair_field
