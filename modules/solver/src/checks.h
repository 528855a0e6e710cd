// Argument checks shared by the solver classes; messages name the function and the sizes.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "lapis/core/error.h"
#include "lapis/solver/types.h"

namespace lapis::solver::detail {

inline std::string dims(Eigen::Index rows, Eigen::Index cols) {
  return std::to_string(rows) + "x" + std::to_string(cols);
}

inline void require_square(const SparseMatrix& A, const char* function) {
  if (A.rows() != A.cols())
    throw InvalidArgument(std::string(function) + ": matrix is " + dims(A.rows(), A.cols()) +
                          ", expected a square matrix");
  if (A.rows() == 0) throw InvalidArgument(std::string(function) + ": matrix is empty (0x0)");
}

inline void require_finite(const SparseMatrix& A, const char* function) {
  const double* v = A.valuePtr();
  for (Eigen::Index k = 0; k < A.nonZeros(); ++k)
    if (!std::isfinite(v[k]))
      throw InvalidArgument(std::string(function) + ": matrix has a non-finite entry (NaN or Inf)");
}

inline void require_rows(const DenseMatrix& B, Eigen::Index n, const char* function,
                         const char* what = "right-hand side") {
  if (B.rows() != n)
    throw InvalidArgument(std::string(function) + ": " + what + " is " + dims(B.rows(), B.cols()) + ", expected " +
                          std::to_string(n) + " rows");
  if (!B.allFinite())
    throw InvalidArgument(std::string(function) + ": " + what + " has a non-finite entry (NaN or Inf)");
}

// `p` holds each of 0..n-1 once.
inline void require_permutation(const std::vector<int>& p, int n, const char* function) {
  if (static_cast<int>(p.size()) != n)
    throw InvalidArgument(std::string(function) + ": ordering has " + std::to_string(p.size()) + " entries, expected " +
                          std::to_string(n));
  std::vector<char> seen(static_cast<size_t>(n), 0);
  for (int v : p) {
    if (v < 0 || v >= n || seen[static_cast<size_t>(v)])
      throw InvalidArgument(std::string(function) + ": ordering is not a permutation of 0.." + std::to_string(n - 1) +
                            " (entry " + std::to_string(v) + (v < 0 || v >= n ? " out of range)" : " repeated)"));
    seen[static_cast<size_t>(v)] = 1;
  }
}

// True when A's sparsity pattern equals the stored one.
inline bool same_pattern(const SparseMatrix& A, const std::vector<int>& outer, const std::vector<int>& inner) {
  if (static_cast<size_t>(A.outerSize() + 1) != outer.size() || static_cast<size_t>(A.nonZeros()) != inner.size())
    return false;
  return std::equal(outer.begin(), outer.end(), A.outerIndexPtr()) &&
         std::equal(inner.begin(), inner.end(), A.innerIndexPtr());
}

}  // namespace lapis::solver::detail
