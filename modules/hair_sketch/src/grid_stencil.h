// The field's normal operator DᵀD + diag(w) applied matrix-free on the uniform grid, in any
// precision, for fields stored node-major (x y z of a node contiguous). The CG iteration
// (double) and the multigrid cycle's finest level (float) both use it: a 25-point sparse
// row costs 25 index loads and gathers per node, the two 7-point passes here stream along
// x-lines with unit-stride neighbour offsets that the compiler vectorizes, and need no
// matrix at all.
#pragma once

#include <omp.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

#include "lapis/hair_sketch/grid.h"

namespace lapis::hair_sketch::detail {

// |N(i)| for node i of an x-line, given the line's y/z neighbour count.
inline int neighbour_count(int i, int nx, int yz_neighbours) {
  return yz_neighbours + (i > 0) + (i + 1 < nx);
}

// out[3i + c] = Σ_{j∈N(i)} src[3j + c] for the nodes of the x-line (j, k); missing
// neighbours (outside the grid) contribute nothing. `zero` is a zero line (3·nx values)
// standing in for a missing y or z neighbour line, so the inner loop has no branches.
template <class T>
inline void line_neighbour_sum(const std::array<int, 3>& dims, const T* src, const T* zero, int j,
                               int k, T* out) {
  const int nx = dims[0], ny = dims[1], nz = dims[2];
  const std::ptrdiff_t line = 3 * static_cast<std::ptrdiff_t>(nx);
  const T* c = src + line * (j + static_cast<std::ptrdiff_t>(ny) * k);
  const T* ym = j > 0 ? c - line : zero;
  const T* yp = j + 1 < ny ? c + line : zero;
  const T* zm = k > 0 ? c - line * ny : zero;
  const T* zp = k + 1 < nz ? c + line * ny : zero;
  for (std::ptrdiff_t f = 0; f < line; ++f) out[f] = ym[f] + yp[f] + zm[f] + zp[f];
  for (std::ptrdiff_t f = 3; f < line; ++f) out[f] += c[f - 3];
  for (std::ptrdiff_t f = 0; f + 3 < line; ++f) out[f] += c[f + 3];
}

// For every node of x-line l (= j + ny·k): node(index, |N(i)|, Σ_{j∈N(i)} src[3j..3j+2]).
template <class T, class F>
inline void neighbour_pass(const std::array<int, 3>& dims, const T* src, const T* zero, T* sum,
                           int l, F&& node) {
  const int nx = dims[0], ny = dims[1], nz = dims[2];
  const int j = l % ny, k = l / ny;
  line_neighbour_sum(dims, src, zero, j, k, sum);
  const int yz = (j > 0) + (j + 1 < ny) + (k > 0) + (k + 1 < nz);
  const std::ptrdiff_t first = static_cast<std::ptrdiff_t>(nx) * l;
  for (int i = 0; i < nx; ++i) node(first + i, neighbour_count(i, nx, yz), sum + 3 * i);
}

// What normal_operator needs besides its operands: a zero x-line and one neighbour-sum line
// per thread. The caller owns it so that iterations reuse it (allocating it on every apply
// cost page faults in each CG iteration and each smoothing step).
template <class T>
struct StencilScratch {
  std::vector<T> zero, sums;
  int threads = 1;

  // Sizes the buffers for x-lines of dims[0] nodes and the current OpenMP thread count.
  void fit(const std::array<int, 3>& dims) {
    const size_t line = 3 * static_cast<size_t>(dims[0]);
    threads = std::max(1, omp_get_max_threads());
    if (zero.size() != line) zero.assign(line, T(0));
    if (sums.size() < line * threads) sums.resize(line * threads);
  }
};

// The operator's two passes, handing each node's result to the caller instead of storing
// it: node(i, v) receives v[c] = ((DᵀD + diag(w)) x)[3i + c], c = 0..2. x  3n; w  n;
// scratch  3n (holds D x scaled by 1/|N|). D(i,i) = −1 and D(i,j) = 1/|N(i)|, so with
// L' = (D x)/|N|:  (DᵀD x)_i = −|N(i)| L'_i + Σ_{j∈N(i)} L'_j.
// The second pass reads x only at node i itself, so `node` may overwrite x[3i..3i+2]
// (the multigrid smoother updates its operand in place this way, one pass per step).
template <class T, class W, class Node>
void normal_operator_visit(const std::array<int, 3>& dims, const W* w, const T* x, T* scratch,
                           StencilScratch<T>& buffers, Node&& node) {
  const int lines = dims[1] * dims[2];
  buffers.fit(dims);
  const T* zero = buffers.zero.data();
  const std::ptrdiff_t line = 3 * static_cast<std::ptrdiff_t>(dims[0]);
#pragma omp parallel num_threads(buffers.threads) if (lines * dims[0] > 20000)
  {
    T* sum = buffers.sums.data() + line * omp_get_thread_num();
#pragma omp for schedule(static)
    for (int l = 0; l < lines; ++l)
      neighbour_pass(dims, x, zero, sum, l, [&](std::ptrdiff_t i, int count, const T* s) {
        const T inv = T(1) / T(count);
        for (std::ptrdiff_t f = 3 * i; f < 3 * i + 3; ++f)
          scratch[f] = inv * (inv * s[f - 3 * i] - x[f]);
      });
#pragma omp for schedule(static)
    for (int l = 0; l < lines; ++l)
      neighbour_pass(dims, scratch, zero, sum, l, [&](std::ptrdiff_t i, int count, const T* s) {
        const T wi = static_cast<T>(w[i]);
        T v[3];
        for (int c = 0; c < 3; ++c)
          v[c] = s[c] - T(count) * scratch[3 * i + c] + wi * x[3 * i + c];
        node(i, static_cast<const T*>(v));
      });
  }
}

// y = (DᵀD + diag(w)) x, or r -= (DᵀD + diag(w)) x when `subtract` (y is then r).
template <class T, class W>
void normal_operator(const std::array<int, 3>& dims, const W* w, const T* x, T* scratch, T* y,
                     bool subtract, StencilScratch<T>& buffers) {
  normal_operator_visit(dims, w, x, scratch, buffers, [&](std::ptrdiff_t i, const T* v) {
    T* yi = y + 3 * i;
    if (subtract)
      yi[0] -= v[0], yi[1] -= v[1], yi[2] -= v[2];
    else
      yi[0] = v[0], yi[1] = v[1], yi[2] = v[2];
  });
}

}  // namespace lapis::hair_sketch::detail
