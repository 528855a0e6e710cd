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

// Calls g(f, s) for the entries f = 3i + c of the x-line (j, k), s = Σ_{j∈N(i)} src[3j + c];
// missing neighbours (outside the grid) contribute nothing. `zero` is a zero line (3·nx
// values) standing in for a missing y or z neighbour line, so the loops have no branches.
// The two end nodes, whose |N(i)| differs, go to `end` instead, after the inner ones. The
// sums are formed where they are used, never stored: one pass over the line.
template <class T, class G, class E>
inline void line_neighbour_visit(const std::array<int, 3>& dims, const T* src, const T* zero,
                                 int j, int k, G&& inner, E&& end) {
  const int nx = dims[0], ny = dims[1], nz = dims[2];
  const std::ptrdiff_t line = 3 * static_cast<std::ptrdiff_t>(nx);
  const T* c = src + line * (j + static_cast<std::ptrdiff_t>(ny) * k);
  const T* ym = j > 0 ? c - line : zero;
  const T* yp = j + 1 < ny ? c + line : zero;
  const T* zm = k > 0 ? c - line * ny : zero;
  const T* zp = k + 1 < nz ? c + line * ny : zero;
  for (std::ptrdiff_t f = 3; f < line - 3; ++f)
    inner(f, ym[f] + yp[f] + zm[f] + zp[f] + c[f - 3] + c[f + 3]);
  for (std::ptrdiff_t f = 0; f < 3; ++f) {
    T s = ym[f] + yp[f] + zm[f] + zp[f];
    if (nx > 1) s += c[f + 3];
    end(f, s);
  }
  for (std::ptrdiff_t f = std::max<std::ptrdiff_t>(3, line - 3); f < line; ++f)
    end(f, ym[f] + yp[f] + zm[f] + zp[f] + c[f - 3]);
}

// What normal_operator needs besides its operands: a zero x-line and one line per thread
// (the operator's values on the line being visited). The caller owns it so that
// iterations reuse it (allocating it on every apply cost page faults in each CG iteration
// and each smoothing step).
template <class T>
struct StencilScratch {
  std::vector<T> zero, lines;
  int threads = 1;

  // Sizes the buffers for x-lines of dims[0] nodes and the current OpenMP thread count.
  void fit(const std::array<int, 3>& dims) {
    const size_t line = 3 * static_cast<size_t>(dims[0]);
    threads = std::max(1, omp_get_max_threads());
    if (zero.size() != line) zero.assign(line, T(0));
    if (lines.size() < line * threads) lines.resize(line * threads);
  }
};

// The operator's two passes, handing each x-line's result to the caller instead of storing
// it: line(f0, len, v) receives v[f] = ((DᵀD + diag(w)) x)[f0 + f] for the len = 3·nx
// entries of one x-line (nodes f0/3 .. f0/3 + nx − 1). x  3n; w  n; scratch  3n (holds D x
// scaled by 1/|N|). D(i,i) = −1 and D(i,j) = 1/|N(i)|, so with L' = (D x)/|N|:
// (DᵀD x)_i = −|N(i)| L'_i + Σ_{j∈N(i)} L'_j. Both passes work a line at a time in
// per-entry loops that vectorize (per-node callbacks did not).
// The second pass reads x only on the line it visits, so `line` may overwrite those
// entries of x (the multigrid smoother updates its operand in place this way).
template <class T, class W, class Line>
void normal_operator_visit(const std::array<int, 3>& dims, const W* w, const T* x, T* scratch,
                           StencilScratch<T>& buffers, Line&& line) {
  const int nx = dims[0], ny = dims[1], nz = dims[2];
  const int lines = ny * nz;
  buffers.fit(dims);
  const T* zero = buffers.zero.data();
  const std::ptrdiff_t len = 3 * static_cast<std::ptrdiff_t>(nx);
#pragma omp parallel num_threads(buffers.threads) if (lines * nx > 20000)
  {
    T* v = buffers.lines.data() + len * omp_get_thread_num();
#pragma omp for schedule(static)
    for (int l = 0; l < lines; ++l) {
      const int j = l % ny, k = l / ny;
      const int yz = (j > 0) + (j + 1 < ny) + (k > 0) + (k + 1 < nz);
      const T* xl = x + len * l;
      T* sl = scratch + len * l;
      const T inv = T(1) / T(yz + 2), inv_end = T(1) / T(neighbour_count(0, nx, yz));
      line_neighbour_visit(
          dims, x, zero, j, k,
          [&](std::ptrdiff_t f, T s) { sl[f] = inv * (inv * s - xl[f]); },
          [&](std::ptrdiff_t f, T s) { sl[f] = inv_end * (inv_end * s - xl[f]); });
    }
#pragma omp for schedule(static)
    for (int l = 0; l < lines; ++l) {
      const int j = l % ny, k = l / ny;
      const int yz = (j > 0) + (j + 1 < ny) + (k > 0) + (k + 1 < nz);
      const T* xl = x + len * l;
      const T* sl = scratch + len * l;
      const T count = T(yz + 2), count_end = T(neighbour_count(0, nx, yz));
      line_neighbour_visit(
          dims, scratch, zero, j, k, [&](std::ptrdiff_t f, T s) { v[f] = s - count * sl[f]; },
          [&](std::ptrdiff_t f, T s) { v[f] = s - count_end * sl[f]; });
      // The weights are zero but at constrained nodes.
      const W* wl = w + static_cast<std::ptrdiff_t>(nx) * l;
      for (int i = 0; i < nx; ++i)
        if (wl[i] != W(0)) {
          const T wi = static_cast<T>(wl[i]);
          for (std::ptrdiff_t f = 3 * i; f < 3 * i + 3; ++f) v[f] += wi * xl[f];
        }
      line(len * l, len, static_cast<const T*>(v));
    }
  }
}

// y = (DᵀD + diag(w)) x, or r -= (DᵀD + diag(w)) x when `subtract` (y is then r).
template <class T, class W>
void normal_operator(const std::array<int, 3>& dims, const W* w, const T* x, T* scratch, T* y,
                     bool subtract, StencilScratch<T>& buffers) {
  normal_operator_visit(dims, w, x, scratch, buffers,
                        [&](std::ptrdiff_t f0, std::ptrdiff_t len, const T* v) {
                          T* yl = y + f0;
                          if (subtract)
                            for (std::ptrdiff_t f = 0; f < len; ++f) yl[f] -= v[f];
                          else
                            for (std::ptrdiff_t f = 0; f < len; ++f) yl[f] = v[f];
                        });
}

}  // namespace lapis::hair_sketch::detail
