// The normal matrices of a weighted least-squares problem, Σ_b w_b A_bᵀ W_b A_b, assembled once and
// split by the roles of the unknowns: the free-free block the solver factorizes and the
// free-fixed block that moves fixed values to the right-hand side.
//
// Why not Eigen's sparse products: the implicit Laplacian systems (thesis Eq. 2.8) have wide
// rows (a coherence row spans two vertices' gradient stencils, ~14 unknowns) and Eigen builds
// every product and sum as its own matrix, transposes, and prunes; on a 16K-vertex merge that
// took 0.8 s of a 2.3 s setup. Here one Gustavson pass per column accumulates every block's
// contribution into a dense row accumulator, columns split across threads.
#pragma once

#include <vector>

#include "lapis/solver/types.h"

namespace lapis::solver::detail {

struct WeightedBlock {
  const SparseMatrix* A;  // m_b by n
  double weight;
  const SparseMatrix* metric = nullptr;  // m_b by m_b symmetric W_b; nullptr: the identity
};

struct NormalMatrices {
  // #free by #free, sorted columns, the lower triangle only (rows ≥ column): the factorization
  // and the ordering read no more, and the upper half was half the assembly's products and
  // memory (Eq. 2.8 at a 50K-vertex merge: ~18 MB).
  SparseMatrix free_free;
  SparseMatrix free_fixed;  // #free by #fixed
};

// free[j], fixed[j]: the unknowns in each role, together a partition of [0, n); free ascending.
NormalMatrices normal_matrices(const std::vector<WeightedBlock>& blocks, const std::vector<int>& free,
                               const std::vector<int>& fixed, int n);

}  // namespace lapis::solver::detail
