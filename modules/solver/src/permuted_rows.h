// The frame both triangular-solve kernels run in: the right-hand sides permuted into the
// factor's ordering with the values of one row stored together (row-major), solved in place,
// and permuted back; the common widths get kernels with the width fixed at compile time.
#pragma once

#include <type_traits>
#include <vector>

#include "lapis/solver/types.h"

namespace lapis::solver::detail {

// X with X(perm[j], :) = Y(j, :) after solve_in_place(Y, width) on Y(j, :) = B(perm[j], :).
// solve_in_place(double* Y, auto width) gets width as std::integral_constant<int, M>, M = 1..4
// or 0 for any other (run-time) count. perm = nullptr: the identity.
template <class SolveInPlace>
DenseMatrix solve_permuted_rows(const int* perm, const DenseMatrix& B, SolveInPlace solve_in_place) {
  const int n = static_cast<int>(B.rows()), m = static_cast<int>(B.cols());
  const size_t w = static_cast<size_t>(m);
  std::vector<double> Y(static_cast<size_t>(n) * w);
  for (int j = 0; j < n; ++j) {
    const int row = perm ? perm[j] : j;
    for (int c = 0; c < m; ++c) Y[static_cast<size_t>(j) * w + static_cast<size_t>(c)] = B(row, c);
  }
  switch (m) {
    case 1:
      solve_in_place(Y.data(), std::integral_constant<int, 1>{});
      break;
    case 2:
      solve_in_place(Y.data(), std::integral_constant<int, 2>{});
      break;
    case 3:
      solve_in_place(Y.data(), std::integral_constant<int, 3>{});
      break;
    case 4:
      solve_in_place(Y.data(), std::integral_constant<int, 4>{});
      break;
    default:
      solve_in_place(Y.data(), std::integral_constant<int, 0>{});
      break;
  }
  DenseMatrix X(n, m);
  for (int j = 0; j < n; ++j) {
    const int row = perm ? perm[j] : j;
    for (int c = 0; c < m; ++c) X(row, c) = Y[static_cast<size_t>(j) * w + static_cast<size_t>(c)];
  }
  return X;
}

// f(std::integral_constant<int, Q>, j) over [j0, j1) in groups of Q = 4 columns, the
// remainder as one group of 1 to 3: kernels that keep Q columns' sums in registers.
template <class F>
void for_column_groups(int j0, int j1, F f) {
  int j = j0;
  for (; j + 4 <= j1; j += 4) f(std::integral_constant<int, 4>{}, j);
  switch (j1 - j) {
    case 3:
      f(std::integral_constant<int, 3>{}, j);
      break;
    case 2:
      f(std::integral_constant<int, 2>{}, j);
      break;
    case 1:
      f(std::integral_constant<int, 1>{}, j);
      break;
    default:
      break;
  }
}

}  // namespace lapis::solver::detail
