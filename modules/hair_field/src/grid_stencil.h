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

#include "lapis/hair_field/grid.h"

namespace lapis::hair_field::detail {

// |N(i)| for node i of an x-line, given the line's y/z neighbour count.
inline int neighbour_count(int i, int nx, int yz_neighbours) { return yz_neighbours + (i > 0) + (i + 1 < nx); }

// Calls g(f, s) for the entries f = 3i + c of an x-line, s = Σ_{j∈N(i)} src[3j + c], given
// the line c and its four y/z neighbour lines; a missing neighbour (outside the grid) is a
// zero line, so the loops have no branches. The two end nodes, whose |N(i)| differs, go to
// `end` instead, after the inner ones. The sums are formed where they are used, never
// stored: one pass over the line.
template <class T, class G, class E>
inline void line_neighbour_visit(int nx, const T* c, const T* ym, const T* yp, const T* zm, const T* zp, G&& inner,
                                 E&& end) {
  const std::ptrdiff_t line = 3 * static_cast<std::ptrdiff_t>(nx);
  for (std::ptrdiff_t f = 3; f < line - 3; ++f) inner(f, ym[f] + yp[f] + zm[f] + zp[f] + c[f - 3] + c[f + 3]);
  for (std::ptrdiff_t f = 0; f < 3; ++f) {
    T s = ym[f] + yp[f] + zm[f] + zp[f];
    if (nx > 1) s += c[f + 3];
    end(f, s);
  }
  for (std::ptrdiff_t f = std::max<std::ptrdiff_t>(3, line - 3); f < line; ++f)
    end(f, ym[f] + yp[f] + zm[f] + zp[f] + c[f - 3]);
}

// What normal_operator needs besides its operands, per thread: planes of the first pass's
// values and one line of the operator's values, plus a zero x-line. The caller owns it so
// that iterations reuse it (allocating it on every apply cost page faults in each CG
// iteration and each smoothing step).
template <class T>
struct StencilScratch {
  static constexpr int planes_per_thread = 5;  // a ring of 3, and the range's last two
  std::vector<T> zero, planes, lines;
  int threads = 1;

  // Sizes the buffers for the grid and the current OpenMP thread count.
  void fit(const std::array<int, 3>& dims) {
    const size_t line = 3 * static_cast<size_t>(dims[0]);
    threads = std::max(1, omp_get_max_threads());
    if (zero.size() != line) zero.assign(line, T(0));
    const size_t plane = line * static_cast<size_t>(dims[1]);
    if (planes.size() < plane * planes_per_thread * threads) planes.resize(plane * planes_per_thread * threads);
    if (lines.size() < line * threads) lines.resize(line * threads);
  }
};

// The operator, handing each x-line's result to the caller instead of storing it:
// line(f0, len, v) receives v[f] = ((DᵀD + diag(w)) x)[f0 + f] for the len = 3·nx entries
// of one x-line (nodes f0/3 .. f0/3 + nx − 1). x  3n; w  n. D(i,i) = −1 and
// D(i,j) = 1/|N(i)|, so with L' = (D x)/|N|: (DᵀD x)_i = −|N(i)| L'_i + Σ_{j∈N(i)} L'_j.
// Both passes work a line at a time in per-entry loops that vectorize (per-node callbacks
// did not).
//
// The two passes are interleaved by z-plane: L' of plane k + 1, then the result on plane k,
// which needs L' on planes k − 1..k + 1 only. L' lives in a ring of three planes per thread
// that stays in cache, and x is read while it is still there: as two whole-grid passes
// through a 3n array, L' went to memory and back and x was read twice.
//
// `line` may overwrite the entries of x on the line it is given (the multigrid smoother
// updates its operand in place): every L' plane that reads a plane of x is formed before
// that plane's results are handed out. Each thread takes a range [k0, k1) of planes and
// forms the L' planes that read its neighbours' planes (k0 − 1, k0, k1 − 1, k1) before a
// barrier, so no neighbour has written them yet.
template <class T, class W, class Line>
void normal_operator_visit(const std::array<int, 3>& dims, const W* w, const T* x, StencilScratch<T>& buffers,
                           Line&& line) {
  const int nx = dims[0], ny = dims[1], nz = dims[2];
  buffers.fit(dims);
  const T* zero = buffers.zero.data();
  const std::ptrdiff_t len = 3 * static_cast<std::ptrdiff_t>(nx);
  const std::ptrdiff_t plane = len * ny;
#pragma omp parallel num_threads(buffers.threads) if (static_cast <std::ptrdiff_t>(nx) * ny * nz > 20000)
  {
    const int t = omp_get_thread_num(), nt = omp_get_num_threads();
    const int k0 = static_cast<int>(static_cast<long long>(nz) * t / nt);
    const int k1 = static_cast<int>(static_cast<long long>(nz) * (t + 1) / nt);
    T* own = buffers.planes.data() + plane * StencilScratch<T>::planes_per_thread * t;
    T* v = buffers.lines.data() + len * t;
    // L' of plane p: the range's last two planes have their own buffers, the others take
    // turns in a ring of three (planes p − 1..p + 1 are alive at once).
    auto buffer_of = [&](int p) -> T* {
      if (p == k1) return own + 4 * plane;
      if (p == k1 - 1) return own + 3 * plane;
      return own + ((p % 3 + 3) % 3) * plane;
    };
    auto first_pass = [&](int k) {
      T* S = buffer_of(k);
      for (int j = 0; j < ny; ++j) {
        const int yz = (j > 0) + (j + 1 < ny) + (k > 0) + (k + 1 < nz);
        const T* xl = x + len * (j + static_cast<std::ptrdiff_t>(ny) * k);
        T* sl = S + len * j;
        const T inv = T(1) / T(yz + 2), inv_end = T(1) / T(neighbour_count(0, nx, yz));
        line_neighbour_visit(
            nx, xl, j > 0 ? xl - len : zero, j + 1 < ny ? xl + len : zero, k > 0 ? xl - plane : zero,
            k + 1 < nz ? xl + plane : zero, [&](std::ptrdiff_t f, T s) { sl[f] = inv * (inv * s - xl[f]); },
            [&](std::ptrdiff_t f, T s) { sl[f] = inv_end * (inv_end * s - xl[f]); });
      }
    };
    if (k0 < k1)
      for (int p : {k0 - 1, k0, k1 - 1, k1})  // k0 = k1 − 1 forms it twice, in the same buffer
        if (p >= 0 && p < nz) first_pass(p);
#pragma omp barrier
    for (int k = k0; k < k1; ++k) {
      if (k + 1 < k1 - 1) first_pass(k + 1);  // k1 − 1 and k1 were formed before the barrier
      const T* S = buffer_of(k);
      const T* Sm = k > 0 ? buffer_of(k - 1) : nullptr;
      const T* Sp = k + 1 < nz ? buffer_of(k + 1) : nullptr;
      for (int j = 0; j < ny; ++j) {
        const int yz = (j > 0) + (j + 1 < ny) + (k > 0) + (k + 1 < nz);
        const std::ptrdiff_t l = j + static_cast<std::ptrdiff_t>(ny) * k;
        const T* xl = x + len * l;
        const T* sl = S + len * j;
        const T count = T(yz + 2), count_end = T(neighbour_count(0, nx, yz));
        line_neighbour_visit(
            nx, sl, j > 0 ? sl - len : zero, j + 1 < ny ? sl + len : zero, Sm ? Sm + len * j : zero,
            Sp ? Sp + len * j : zero, [&](std::ptrdiff_t f, T s) { v[f] = s - count * sl[f]; },
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
}

// y = (DᵀD + diag(w)) x, or r -= (DᵀD + diag(w)) x when `subtract` (y is then r).
template <class T, class W>
void normal_operator(const std::array<int, 3>& dims, const W* w, const T* x, T* y, bool subtract,
                     StencilScratch<T>& buffers) {
  normal_operator_visit(dims, w, x, buffers, [&](std::ptrdiff_t f0, std::ptrdiff_t len, const T* v) {
    T* yl = y + f0;
    if (subtract)
      for (std::ptrdiff_t f = 0; f < len; ++f) yl[f] -= v[f];
    else
      for (std::ptrdiff_t f = 0; f < len; ++f) yl[f] = v[f];
  });
}

}  // namespace lapis::hair_field::detail
