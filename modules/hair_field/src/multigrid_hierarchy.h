// Galerkin geometric multigrid for the field's normal matrix A = DᵀD + ω²·diag(w) on the
// uniform grid: trilinear prolongation, coarse operators Pᵀ A P, Chebyshev–Jacobi smoothing
// (a polynomial in diag(A)⁻¹A: parallel, and the ω² = 10⁴ rows are simply scaled away),
// dense LDLᵀ on the coarsest level.
//
// Constrained ("pinned") fine nodes get a zero row in the first prolongation. Their error
// is removed by the smoother alone (Jacobi is nearly exact on a row whose diagonal is 10⁴
// times its off-diagonal sum), and the coarse space then models the bi-Laplacian of the
// free nodes around them. Interpolating through pinned nodes instead made every coarse
// node near a constraint stiff, so smooth error next to constraints had no coarse
// representation: 25 CG iterations at 50K after a stroke, 15 with the zero rows (the
// remaining smoothing near constraints, Gauss–Seidel sweeps, no longer helps).
// Pinning or freeing a node changes level 1 only by the terms of its own row of P, so edits
// update the hierarchy in place instead of rebuilding it.
#pragma once

#include <array>
#include <unordered_map>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include "grid_stencil.h"
#include "lapis/hair_field/grid.h"

namespace lapis::hair_field::detail {

// Precision of the cycle: the preconditioner only needs a few digits.
using Real = float;
using VectorR = Eigen::Matrix<Real, Eigen::Dynamic, 1>;
using FieldF = Eigen::Matrix<Real, Eigen::Dynamic, 3, Eigen::RowMajor>;
using RowSparseD = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;
using RowSparseF = Eigen::SparseMatrix<Real, Eigen::RowMajor, int>;

// Below this many stored entries a sparse product runs on one thread. The threshold counts
// entries, not rows: level 1 of a 50K grid has only 7.4K rows but 0.9M entries (up to 125
// a row), the costliest product of the cycle, and a row threshold left it on one thread.
inline constexpr std::ptrdiff_t parallel_nonzeros = 50000;
// Element-wise passes: below this many nodes one thread.
inline constexpr int parallel_nodes = 20000;

// The cycle's parameters, as MultigridFieldOptions (multigrid_field_solver.h) gives them;
// the defaults live there.
struct MultigridOptions {
  int smoothing_degree = 0;    // Chebyshev polynomial degree, pre and post
  int cycle_index = 0;         // coarse-grid corrections per visit of the finest level
  int coarse_cycle_index = 0;  // ... and per visit of each coarser level (1: V-cycle;
                               // 0: 4 on hierarchies of 5 or more levels, else 2, and
                               // at most 2 into a level whose products run on one thread)
  double smoothing_range = 0;  // smooth eigenvalues of D⁻¹A in [range·λmax, λmax]
  int coarsest_nodes = 0;      // dense LDLᵀ at or below this size
  bool cubic = false;          // cubic (else linear) prolongation
};

class MultigridHierarchy {
 public:
  // weights  n, the diagonal added to DᵀD (ω² at constrained nodes).
  MultigridHierarchy(const Grid& grid, const Eigen::VectorXd& weights, MultigridOptions options);

  // Adds delta[k] to A(node[k], node[k]) on the fine level and the matching Galerkin
  // change to every coarse level.
  void add_to_diagonal(const std::vector<std::pair<int, double>>& changes);

  // z ≈ A⁻¹ r by one cycle from zero (a symmetric positive definite preconditioner).
  // r and z are n × 3; r is left as it was, z's storage is exchanged with the cycle's.
  // With `dots`, also dots[c] = Σ_i dot_with[3i + c] z[3i + c] (dot_with 3n, node-major),
  // formed as the cycle's last step writes z instead of in a pass of its own.
  void apply(FieldF& r, FieldF& z, const double* dot_with = nullptr, double dots[3] = nullptr);

  int levels() const { return static_cast<int>(levels_.size()); }
  // Coarse corrections per visit of level l (1 on the level above the coarsest).
  int corrections(int l) const { return corrections_[l]; }
  std::array<int, 3> dims(int level) const { return levels_[level].dims; }
  std::int64_t operator_nonzeros() const;

 private:
  struct Level {
    std::array<int, 3> dims{};
    RowSparseD A;   // double master, accumulates edits exactly
    RowSparseF Af;  // float copy used by the cycle (same pattern as A; empty if matrix_free)
    RowSparseF P;   // prolongation from the next coarser level (n × n_coarse); empty
                    // on the finest level unless cubic (grid_transfer.h applies it)
    RowSparseF R;   // Pᵀ, row-major for a gather-style restriction
    RowSparseD Pd;  // P in double, to push edits down
    VectorR inv_diag;
    VectorR gershgorin;  // per row Σ|a_ij| / a_ii: bounds λ(D⁻¹A)
    Real lambda_max = 0;
    FieldF x, b, r, d;  // work vectors
    FieldF d2;          // sparse levels: the next Chebyshev direction while d is still read
    FieldF b0, e;       // coarse levels in a W-cycle: the right-hand side and the sum of
                        // the corrections while a further correction is solved
    // The finest level applies A matrix-free (grid_stencil.h) with these weights (ω² at
    // constrained nodes).
    bool matrix_free = false;
    VectorR weights;
    VectorR inv_diag3;  // inv_diag repeated per entry (x y z), for per-entry loops
    StencilScratch<Real> buffers;
    Eigen::VectorXd base_diag;  // diagonal without constraints
  };
  struct Entry {
    int i, j;
    double v;
  };
  void update_level(int l, const std::vector<Entry>& T);
  void free_set_change(int s, double sign, std::unordered_map<long long, double>& acc) const;
  void set_prolongation_row(int s, bool free);
  void cycle(int l);
  void residual(Level& L);  // r = b − A x
  // One Chebyshev step of smooth(): from_x for the first step from a non-zero x.
  // last: the smoothing's last step; post: of a post-smoothing.
  void chebyshev_step(Level& L, bool from_x, bool& pending, const Real* r_in, Real a, Real c, bool last, bool post);
  void smooth(Level& L, bool zero_initial);
  void refresh_row(Level& L, int row);
  void factor_coarsest();

  MultigridOptions opt_;
  std::vector<Level> levels_;
  std::vector<int> corrections_;  // per level, see corrections()
  Eigen::LDLT<Eigen::MatrixXd> coarsest_;
  Eigen::MatrixXd coarse_rhs_;        // the coarsest solve's right-hand side, solved in place
  Eigen::VectorXd fine_weights_;      // the weights on the fine diagonal, exact
  std::vector<char> pinned_;          // fine nodes with a weight: their prolongation row is zero
  const double* dot_with_ = nullptr;  // apply()'s dot products, formed in the last step
  bool dot_done_ = false;
  std::vector<double> dot_partials_;  // per thread, 8 doubles apart
};

}  // namespace lapis::hair_field::detail
