// Private: the rows of implicit Laplacian editing's first system (thesis Eq. 2.8): E_L
// (Eq. 2.6), E_R (Eq. 2.7) with its pair-graph metric, the transformation constraints
// M_c = W_c, and the Laplacian blend terms E_T of Poisson merging (§3.3.3). Each is a
// sparse block over the work mesh's vertices, linear in the unknown positions through the
// gradient stencils (Eq. 2.3–2.5).
#pragma once

#include <vector>

#include "implicit_rest.h"
#include "lapis/solver/types.h"

namespace lapis::mesh_deform::detail {

struct FirstSystemRows {
  solver::SparseMatrix laplacian;         // E_L: D(ṽ_i) − M_i δ_i per free vertex
  solver::SparseMatrix coherence;         // E_R: three rows g_i(a) per vertex in a 2-ring pair
  solver::SparseMatrix coherence_metric;  // the pair graph's Laplacian ⊗ I₃ (0 by 0 without pairs)
  solver::SparseMatrix transform;         // M_c = W_c: three rows per constrained vertex
  std::vector<int> transform_vertex;      // vertex of each three transformation rows
  std::vector<int> transform_handle;      // its region handle, -1: the identity (fixed border)
  solver::SparseMatrix blend;             // E_T: one row per usable LaplacianBlend
};

// s  the work mesh's Laplacian on the displaced positions, deltaP its δ_i (#V' by 3), G the
// gradient stencils there; free and constrained partition the work mesh's vertices.
FirstSystemRows first_system_rows(const WorkMesh& w, const Stencil& s, const GradientStencils& G,
                                  const Vertices& deltaP, const std::vector<int>& free,
                                  const std::vector<int>& constrained, const std::vector<LaplacianBlend>& blends);

}  // namespace lapis::mesh_deform::detail
