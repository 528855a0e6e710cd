// Private: the operator Spectra's shift-invert mode applies, y = (K − σM)⁻¹ x, as a Cholesky
// factor of K − σM computed once per shift. Spectra calls set_shift() once and perform_op()
// once per Lanczos step; each step is one back-substitution.
#pragma once

#include <Eigen/Core>

#include "lapis/solver/cholesky.h"

namespace lapis::solver::detail {

class ShiftInvertOperator {
 public:
  using Scalar = double;  // Spectra's operator concept

  ShiftInvertOperator(const SparseMatrix& K, const SparseMatrix& M) : K_(K), M_(M) {}

  Eigen::Index rows() const { return K_.rows(); }
  Eigen::Index cols() const { return K_.cols(); }

  // Factorizes K − σM; throws NotPositiveDefinite from the Cholesky.
  void set_shift(double sigma) {
    const SparseMatrix A = K_ - sigma * M_;
    chol_.compute(A);
  }

  void perform_op(const double* x_in, double* y_out) {
    rhs_ = Eigen::Map<const Eigen::VectorXd>(x_in, rows());
    Eigen::Map<Eigen::VectorXd>(y_out, rows()) = chol_.solve(rhs_);
    ++solves_;
  }

  int solves() const { return solves_; }
  const FactorReport& factor_report() const { return chol_.report(); }

 private:
  const SparseMatrix& K_;
  const SparseMatrix& M_;
  Cholesky chol_;
  DenseMatrix rhs_;
  int solves_ = 0;
};

}  // namespace lapis::solver::detail
