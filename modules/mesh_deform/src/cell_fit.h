// Private: the local transform T of one Laplacian node fitted to its cell (Wang et al. §3.4,
// Eq. 7–8): min Σ ω ‖e′ − T e‖² over the cell vectors e (rest) and e′ (deformed), with T a
// rotation R1, s R1, S R1 or R2 S R1. Everything the fits need from the deformed cell is
// A = Σ ω e′ eᵀ, and from the rest cell C0 = Σ ω e eᵀ, so a fit costs a few 3x3 products
// after the cell is gathered.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "lapis/mesh_deform/edge_laplacian.h"

namespace lapis::mesh_deform::detail {

// The rest cell of one node.
struct RestCell {
  Eigen::Matrix3d C0 = Eigen::Matrix3d::Zero();      // Σ ω e eᵀ
  Eigen::Matrix3d U = Eigen::Matrix3d::Identity();   // principal axes of C0 (columns), ascending
  Eigen::Vector3d lambda = Eigen::Vector3d::Zero();  // their eigenvalues
  Eigen::Vector3i group = Eigen::Vector3i(0, 1, 2);  // axes with equal eigenvalues share a group
};

// C0 and, for ScaleFrame::RestPrincipal, its eigen-decomposition; eigenvalues closer than
// kEqualEigenvalues × the largest count as equal (their eigenvectors are arbitrary, or
// rotate under rounding, so the scale across them must be one number).
RestCell rest_cell(const Eigen::Matrix3d& C0, bool principal);
constexpr double kEqualEigenvalues = 1e-3;

// The fitted transforms of one node and the rotation fits' warm starts.
struct CellState {
  Eigen::Matrix3d T = Eigen::Matrix3d::Identity();
  Eigen::Quaterniond q1 = Eigen::Quaterniond::Identity();  // R1
  Eigen::Quaterniond q2 = Eigen::Quaterniond::Identity();  // R2 (CellTransform::Full)
};

// Fits state.T to A = Σ ω e′ eᵀ. Returns true when a rotation fit needed the SVD fallback.
bool fit_cell(const Eigen::Matrix3d& A, const RestCell& rest, CellTransform transform, ScaleFrame frame,
              CellState& state);

}  // namespace lapis::mesh_deform::detail
