// The solid subspace of Zhao et al. §4: a coarse tetrahedral mesh around the surface whose
// vertices carry a position x_i and a linear map M_i, interpolated to the surface by the
// modified barycentric coordinates of Eq. 7, x(u) = Σ_i φ_i(u) (x_i + M_i (u − u_i)), and the
// two regularisers of Eq. 8 that keep the interpolated deformation gradient smooth.
//
// Output coordinate k depends only on x_{i,k} and row k of each M_i, so one matrix serves x, y
// and z: the unknowns are Z, 4·#TV by 3, rows 4i (x_i) and 4i + 1 … 4i + 3 (M_i's columns),
// and P′ = C Z (Eq. 9).
#pragma once

#include <vector>

#include "lapis/geometry/tet_mesh.h"
#include "lapis/solver/types.h"

namespace lapis::mesh_deform {

struct SubspaceEmbedding {
  solver::SparseMatrix C;   // #V by 4·#TV (Eq. 9), rows: at most 16 entries, φ summing to 1
  std::vector<int> tet_of;  // #V: the tet each surface vertex lies in (or is bound to)
  int strays = 0;           // surface vertices outside every tet, bound to the nearest one
};

// Locates every vertex of P (#V by 3) in tets and builds C: row j holds φ_a at column 4a and
// φ_a (p_j − u_a)_l at column 4a + 1 + l for the corners a of p_j's tet. Throws like
// geometry::TetLocator, and InvalidArgument for a non-finite P.
SubspaceEmbedding embed_in_subspace(const geometry::TetMesh& tets, const geometry::Vertices& P);

// Z of the rest state: x_i = u_i, M_i = I (then C Z reproduces P exactly).
solver::DenseMatrix rest_coefficients(const geometry::TetMesh& tets);

// Z of the affine map u ↦ G u + t: x_i = G u_i + t, M_i = G.
solver::DenseMatrix affine_coefficients(const geometry::TetMesh& tets, const Eigen::Matrix3d& G,
                                        const Eigen::Vector3d& t);

// Rows B_disc of E_disc = Σ over interior faces f of ∫_f ‖J_T1 − J_T2‖²_F (spec §1.3, in lieu of
// Huang et al. 2009's definition, which the paper only cites): J is affine in each tet, so the
// face's three edge midpoints, weighted area/3, integrate the quadratic jump exactly.
// 3 rows per midpoint, 4·#TV columns, shared by x, y and z; zero on every affine map.
solver::SparseMatrix discontinuity_rows(const geometry::TetMesh& tets);

// Rows B_vibr of E_vibr = Σ_T Σ_{i∈T} vol(T)^{2/3} ‖M_i − J^lin_T‖²_F, J^lin_T the gradient of the
// linear interpolation of the x's in T (spec §1.3): ties each M_i to the gradients around it.
// 3 rows per (tet, corner); zero on every affine map.
solver::SparseMatrix vibration_rows(const geometry::TetMesh& tets);

}  // namespace lapis::mesh_deform
