// Private: the parts of Zhao et al.'s Eq. 11 that depend only on the mesh, the features and
// the subspace, assembled once; the handle rows (Eq. 4) join them per selection. Unknowns are
// the subspace coefficients Z (4·#TV by 3, solid_subspace.h), so every block is AᵀA of rows
// that act on one coordinate and serve x, y and z alike.
#pragma once

#include <vector>

#include "lapis/geometry/tet_mesh.h"
#include "lapis/mesh_deform/salient_deformer.h"
#include "lapis/mesh_deform/solid_subspace.h"
#include "lapis/solver/types.h"

namespace lapis::mesh_deform::detail {

struct SalientSystem {
  solver::SparseMatrix C;            // #V by 4·#TV (Eq. 9)
  solver::SparseMatrix Ct;           // its transpose: right-hand sides are Cᵀ Y
  solver::SparseMatrix L;            // #V by #V cotangent Laplacian (geometry's sign, unnormalised)
  Vertices delta;                    // L P at rest: Eq. 3's δ
  std::vector<int> detail_vertices;  // vertices outside every feature: Eq. 3's sum
  std::vector<Feature> features;
  std::vector<double> weight;     // w_i of Eq. 2, per feature
  std::vector<Vertices> offsets;  // per feature, p_j − c_i at rest (|F_i| by 3)
  solver::SparseMatrix normal;    // Eq. 11's normal matrix without the handle rows
};

// Assembles E_sfp (Eq. 1–2, centred rows), α E_ldp (Eq. 3), γ E_disc and λ E_vibr (Eq. 8).
SalientSystem assemble_salient_system(const TriMesh& mesh, std::vector<Feature> features, const geometry::TetMesh& tets,
                                      solver::SparseMatrix C, const SalientOptions& options);

// β Σ_h C_hᵀ C_h over the given vertices (Eq. 4 projected by Eq. 9).
solver::SparseMatrix handle_normal(const solver::SparseMatrix& C, const std::vector<int>& vertices, double beta);

}  // namespace lapis::mesh_deform::detail
