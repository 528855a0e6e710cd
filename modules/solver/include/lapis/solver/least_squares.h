// Weighted sparse linear least squares with hard constraints:
//   min_x  Σ_b w_b ‖A_b x − r_b‖²_{W_b}   subject to  x_i = c_i for fixed i,
// where ‖y‖²_W = yᵀ W y (W = I unless a block gives its metric),
// the shape of every Laplacian / Poisson editing system in Lapis (thesis Eq. 2.1, 2.8, 4.x).
// Precompute once (assemble and factorize the normal matrix of the free unknowns), then
// solve() per frame for new right-hand sides r_b and fixed values c, several columns at once.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "lapis/solver/cholesky.h"

namespace lapis::solver {

class LeastSquares {
 public:
  // n  number of unknowns (per column).
  explicit LeastSquares(int n, CholeskyOptions options = {});
  ~LeastSquares();
  LeastSquares(LeastSquares&&) noexcept;
  LeastSquares& operator=(LeastSquares&&) noexcept;

  // A  m_b by n block of rows, weight w_b > 0 (squared-norm weight). Returns the block's id,
  // the position of its right-hand side in solve(). Invalidates the precomputation. The block
  // is kept: pass a temporary (e.g. a builder's matrix()) and it is taken without a copy.
  int add_block(SparseMatrix A, double weight, std::string name = {});
  // A block whose residual is measured in the metric W (m_b by m_b, symmetric positive
  // semi-definite): w_b (A x − r)ᵀ W (A x − r). Energies over pairs, Σ_(i,j) ‖a_i x − a_j x‖²,
  // are Aᵀ (Dᵀ D) A with one row a_i per item instead of one per pair: the same normal matrix
  // from far fewer, shorter products (the implicit Laplacian's E_R, thesis Eq. 2.7).
  int add_block(SparseMatrix A, double weight, std::string name, SparseMatrix metric);
  // Block `id`'s matrix and metric (an empty matrix when it has none), as added. Throw
  // InvalidArgument for an id out of range.
  const SparseMatrix& block_matrix(int id) const;
  const SparseMatrix& block_metric(int id) const;
  // Unknowns held at given values (eliminated, not penalized). Invalidates the precomputation.
  void set_fixed(std::vector<int> indices);

  // A sparse graph over the n unknowns (pattern of an n by n matrix) whose nested dissection,
  // widened to the normal matrix's couplings, orders the factorization instead of CHOLMOD's
  // own choice (skeleton_nested_dissection, ordering.h): for blocks with wide stencils, whose
  // normal matrix is far denser than the mesh (the implicit Laplacian's Eq. 2.8). An empty
  // matrix restores CHOLMOD's choice. Invalidates the precomputation. Throws InvalidArgument
  // if it is not n by n.
  void set_ordering_skeleton(SparseMatrix skeleton);

  // Assembles Σ w_b A_bᵀ A_b over the free unknowns and factorizes it. Throws
  // NotPositiveDefinite when the free unknowns are under-determined.
  void precompute();
  bool precomputed() const;

  // rhs[b]  m_b by k right-hand side of block b (an empty matrix means zero);
  // fixed_values  #fixed by k, in set_fixed's order. Returns x, n by k.
  DenseMatrix solve(const std::vector<DenseMatrix>& rhs, const DenseMatrix& fixed_values) const;
  // solve() followed by refinement_steps corrections from the blocks' own residuals (the
  // corrected semi-normal equations, Björck): each step costs a product with every block and
  // one more back-substitution, and takes the error from cond(A)² toward cond(A) times the
  // unit roundoff, for systems whose normal matrix is too ill-conditioned for one solve.
  DenseMatrix solve(const std::vector<DenseMatrix>& rhs, const DenseMatrix& fixed_values, int refinement_steps) const;

  // Assembles Σ w_b A_bᵀ r_b restricted to free unknowns, minus the fixed coupling: the
  // right-hand side solve() factors, exposed for callers that batch several solves.
  DenseMatrix normal_rhs(const std::vector<DenseMatrix>& rhs, const DenseMatrix& fixed_values) const;

  int unknowns() const;
  int num_blocks() const;
  const std::vector<int>& fixed() const;
  const std::vector<int>& free() const;
  const Cholesky& factor() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lapis::solver
