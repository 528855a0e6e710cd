// The field's normal operator DᵀD + diag(w) applied matrix-free on the uniform grid, in any
// precision, for fields stored node-major (x y z of a node contiguous). The CG iteration
// (double) and the multigrid cycle's finest level (float) both use it: a 25-point sparse
// row costs 25 index loads and gathers per node, the two 7-point passes here stream along
// x-lines with unit-stride neighbour offsets that the compiler vectorizes, and need no
// matrix at all.
#pragma once

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

// y = (DᵀD + diag(w)) x, or r -= (DᵀD + diag(w)) x when `subtract` (y is then r).
// x, y  3n; w  n; scratch  3n (holds D x scaled by 1/|N|). D(i,i) = −1 and
// D(i,j) = 1/|N(i)|, so with L' = (D x)/|N|:  (DᵀD x)_i = −|N(i)| L'_i + Σ_{j∈N(i)} L'_j.
template <class T, class W>
void normal_operator(const std::array<int, 3>& dims, const W* w, const T* x, T* scratch, T* y,
                     bool subtract) {
  const int lines = dims[1] * dims[2];
  const std::vector<T> zero(3 * static_cast<size_t>(dims[0]), T(0));
#pragma omp parallel if (lines * dims[0] > 20000)
  {
    std::vector<T> sum(zero.size());
#pragma omp for schedule(static)
    for (int l = 0; l < lines; ++l)
      neighbour_pass(dims, x, zero.data(), sum.data(), l,
                     [&](std::ptrdiff_t i, int count, const T* s) {
                       const T inv = T(1) / T(count);
                       for (std::ptrdiff_t f = 3 * i; f < 3 * i + 3; ++f)
                         scratch[f] = inv * (inv * s[f - 3 * i] - x[f]);
                     });
#pragma omp for schedule(static)
    for (int l = 0; l < lines; ++l)
      neighbour_pass(dims, scratch, zero.data(), sum.data(), l,
                     [&](std::ptrdiff_t i, int count, const T* s) {
                       const T wi = static_cast<T>(w[i]);
                       for (std::ptrdiff_t f = 3 * i; f < 3 * i + 3; ++f) {
                         const T v = s[f - 3 * i] - T(count) * scratch[f] + wi * x[f];
                         y[f] = subtract ? y[f] - v : v;
                       }
                     });
  }
}

}  // namespace lapis::hair_sketch::detail
