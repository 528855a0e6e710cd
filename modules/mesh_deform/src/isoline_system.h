// Private: the reduced normal equations of Au et al. 2007, assembled in one pass over the
// vertices without forming W_x, L W_x or W_δ:
//   UᵀU = (L W_x)ᵀ(L W_x) + ω² W_xᵀΦᵀΦW_x + β² MᵀM      (§4.2, Eq. 6; 4m by 4m)
//   P   = (L W_x)ᵀ W_δ                                  (§4.3, Eq. 10; 4m by 3m)
//   G   = W_xᵀΦᵀQ per handle, so that ω² G C is Eq. 10's handle term (Botsch & Kobbelt's
//         affine representation: a region handle's C is its 3×4 transform, Q = [x̄ 1]).
// The three parts are kept apart so that the weights can be chosen after assembly.
#pragma once

#include <vector>

#include <Eigen/SparseCore>

#include "isoline_basis.h"

namespace lapis::mesh_deform::detail {

// Vertices that the handle term ΦX = QC holds: moved by one affine transform (a region handle,
// or the fixed region with the identity), or one vertex moved by a translation (a point handle).
struct HandleGroup {
  std::vector<int> vertices;
  bool affine = true;
};

struct IsolineSystem {
  solver::DenseMatrix laplacian;       // (L W_x)ᵀ(L W_x)
  solver::DenseMatrix handles;         // W_xᵀΦᵀΦW_x, unweighted
  solver::DenseMatrix smoothness;      // MᵀM over 4×4 blocks of neighbouring isolines
  solver::DenseMatrix P;               // (L W_x)ᵀ W_δ
  std::vector<solver::DenseMatrix> G;  // per group: 4m by 4 (affine) or 4m by 1 (point)
  int handle_rows = 0;                 // vertices in all groups
};

// L  #V by #V cotangent Laplacian (symmetric); delta  #V by 3 rest Laplacian coordinates L X̄,
// normalized like the basis.
IsolineSystem assemble_isoline_system(const IsolineBasis& basis, const Eigen::SparseMatrix<double>& L,
                                      const geometry::Vertices& delta, const std::vector<HandleGroup>& groups);

// Wᵀ Y for Y  #V by 3 (Eq. 6's W_xᵀ Lᵀ δ when Y = L δ).
solver::DenseMatrix basis_transpose_times(const IsolineBasis& basis, const geometry::Vertices& Y);

}  // namespace lapis::mesh_deform::detail
