// Private: the arrays of a CHOLMOD simplicial factor (int indices) as the solver's own
// kernels read them. Column j holds rows i[p[j] .. p[j] + nz[j]) with values x[...], sorted,
// the diagonal first (LDLᵀ: D(j, j) in place of L's unit diagonal).
#pragma once

#include <cholmod.h>

namespace lapis::solver::detail {

template <class Value>  // double to modify the values, const double to read them
struct SimplicialView {
  const int* p;
  const int* i;
  const int* nz;
  Value* x;
  const int* perm;
  int n;

  explicit SimplicialView(const cholmod_factor& L)
      : p(static_cast<const int*>(L.p)),
        i(static_cast<const int*>(L.i)),
        nz(static_cast<const int*>(L.nz)),
        x(static_cast<Value*>(L.x)),
        perm(static_cast<const int*>(L.Perm)),
        n(static_cast<int>(L.n)) {}

  // Rows are sorted with the diagonal first, so the parent in the elimination tree is the
  // first row below it.
  int parent(int j) const { return nz[j] > 1 ? i[p[j] + 1] : -1; }

  // Σ nnz of the columns: changes when an update adds fill (caches keyed on the pattern).
  long long entries() const {
    long long total = 0;
    for (int j = 0; j < n; ++j) total += nz[j];
    return total;
  }
};

}  // namespace lapis::solver::detail
