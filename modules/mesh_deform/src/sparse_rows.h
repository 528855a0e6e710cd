// Private: builds a sparse matrix row by row (the least-squares blocks of every deformer).
#pragma once

#include <vector>

#include <Eigen/SparseCore>

#include "lapis/solver/types.h"

namespace lapis::mesh_deform::detail {

class SparseRows {
 public:
  explicit SparseRows(int cols) : cols_(cols) {}
  void begin_row() { ++rows_; }
  // Adds v at (current row, col); repeated columns are summed.
  void add(int col, double v) { t_.emplace_back(rows_ - 1, col, v); }
  int rows() const { return rows_; }
  solver::SparseMatrix matrix() const {
    solver::SparseMatrix A(rows_, cols_);
    A.setFromTriplets(t_.begin(), t_.end());
    A.makeCompressed();
    return A;
  }

 private:
  int cols_;
  int rows_ = 0;
  std::vector<Eigen::Triplet<double, int>> t_;
};

// Appends the row of D (δ_i = Σ_j w_ij (v_j − v_i)) for vertex i of a stencil-like CSR.
template <class StencilT>
void add_laplacian_row(SparseRows& rows, const StencilT& s, int i) {
  rows.begin_row();
  double diag = 0;
  for (int k = s.offsets[i]; k < s.offsets[i + 1]; ++k) {
    rows.add(s.nbr[k], s.w[k]);
    diag -= s.w[k];
  }
  rows.add(i, diag);
}

}  // namespace lapis::mesh_deform::detail
