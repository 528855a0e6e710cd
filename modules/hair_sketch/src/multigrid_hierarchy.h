// Galerkin geometric multigrid for the field's normal matrix A = DᵀD + ω²·diag(w) on the
// uniform grid: trilinear prolongation, coarse operators Pᵀ A P (so the soft constraints'
// huge diagonal reaches every level correctly), Chebyshev–Jacobi smoothing (a polynomial in
// diag(A)⁻¹A: parallel, and the ω² = 10⁴ rows are simply scaled away) plus Gauss–Seidel on
// the rows next to constraints, dense LDLᵀ on the coarsest level. A changed fine weight is
// a rank-1 change p pᵀ of each coarse operator, so edits update the hierarchy in place
// instead of rebuilding it.
#pragma once

#include <array>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include "lapis/hair_sketch/grid.h"

namespace lapis::hair_sketch::detail {

// Precision of the cycle: the preconditioner only needs a few digits.
using Real = float;
using VectorR = Eigen::Matrix<Real, Eigen::Dynamic, 1>;
using FieldF = Eigen::Matrix<Real, Eigen::Dynamic, 3, Eigen::RowMajor>;
using RowSparseD = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;
using RowSparseF = Eigen::SparseMatrix<Real, Eigen::RowMajor, int>;

struct MultigridOptions {
  int smoothing_degree = 3;      // Chebyshev polynomial degree, pre and post
  int cycle_index = 1;           // 1: V-cycle, 2: W-cycle
  double smoothing_range = 0.12; // smooth eigenvalues of D⁻¹A in [range·λmax, λmax]
  int coarsest_nodes = 500;      // dense LDLᵀ at or below this size
  bool cubic = false;            // cubic (else linear) prolongation
  int band_sweeps = 2;           // symmetric Gauss–Seidel sweeps near constraints
};

class MultigridHierarchy {
 public:
  // weights  n, the diagonal added to DᵀD (ω² at constrained nodes).
  MultigridHierarchy(const Grid& grid, const Eigen::VectorXd& weights, MultigridOptions options);

  // Adds delta[k] to A(node[k], node[k]) on the fine level and the matching Galerkin
  // change to every coarse level.
  void add_to_diagonal(const std::vector<std::pair<int, double>>& changes);

  // z ≈ A⁻¹ r by one cycle from zero (a symmetric positive definite preconditioner).
  void apply(const FieldF& r, FieldF& z);

  int levels() const { return static_cast<int>(levels_.size()); }
  std::array<int, 3> dims(int level) const { return levels_[level].dims; }
  std::int64_t operator_nonzeros() const;

 private:
  struct Level {
    std::array<int, 3> dims{};
    RowSparseD A;       // double master, accumulates edits exactly
    RowSparseF Af;      // float copy used by the cycle (same pattern as A)
    RowSparseF P;       // prolongation from the next coarser level (n × n_coarse)
    RowSparseF R;       // Pᵀ, row-major for a gather-style restriction
    RowSparseD Pd;      // P in double, to push edits down
    VectorR inv_diag;
    VectorR gershgorin;  // per row Σ|a_ij| / a_ii: bounds λ(D⁻¹A)
    Real lambda_max = 0;
    FieldF x, b, r, d;  // work vectors
    Eigen::VectorXd base_diag;  // diagonal without constraints
    std::vector<int> band;      // rows touched by constraints and their neighbours
  };
  void cycle(int l);
  void smooth(Level& L, bool zero_initial);
  void band_gauss_seidel(Level& L);
  void refresh_band(Level& L);
  void refresh_row(Level& L, int row);
  void factor_coarsest();

  MultigridOptions opt_;
  std::vector<Level> levels_;
  Eigen::LDLT<Eigen::MatrixXd> coarsest_;
};

}  // namespace lapis::hair_sketch::detail
