// The multigrid's trilinear transfers between the finest grid and the next coarser one,
// applied matrix-free. The coarse grid has dims/2 + 1 nodes per axis: fine node 2c lies on
// coarse node c, an odd fine node averages its two coarse neighbours, and P is the tensor
// product of these 1D rules with zero rows at the pinned (constrained) fine nodes
// (multigrid_hierarchy.h says why). As CSR products the two transfers read P's 3.4 stored
// entries per fine node (27 MB at 1M nodes) in each direction; here they read only the
// vectors.
#pragma once

#include <omp.h>

#include <array>
#include <cstddef>
#include <vector>

namespace lapis::hair_field::detail {

// 1D rule: the coarse neighbours of fine coordinate f (one with weight 1, or two with 1/2).
struct CoarseNeighbours {
  int first, count;
  float weight;
};
inline CoarseNeighbours coarse_neighbours(int f) {
  return f % 2 == 0 ? CoarseNeighbours{f / 2, 1, 1.0f} : CoarseNeighbours{(f - 1) / 2, 2, 0.5f};
}

// xf += P xc, 3 values per node; pinned fine nodes are left unchanged (their row of P is 0).
template <class T>
void prolong_add(const std::array<int, 3>& fd, const std::array<int, 3>& cd, const char* pinned, const T* xc, T* xf) {
  const std::ptrdiff_t cline = 3 * static_cast<std::ptrdiff_t>(cd[0]);
  const std::ptrdiff_t fline = 3 * static_cast<std::ptrdiff_t>(fd[0]);
  const int lines = fd[1] * fd[2];
#pragma omp parallel if (static_cast <std::ptrdiff_t>(lines) * fd[0] > 20000)
  {
    std::vector<T> t(static_cast<size_t>(cline));  // the coarse line interpolated in y and z
#pragma omp for schedule(static)
    for (int l = 0; l < lines; ++l) {
      const int j = l % fd[1], k = l / fd[1];
      const CoarseNeighbours ny = coarse_neighbours(j), nz = coarse_neighbours(k);
      const T w = static_cast<T>(ny.weight * nz.weight);
      std::fill(t.begin(), t.end(), T(0));
      for (int c = 0; c < nz.count; ++c)
        for (int b = 0; b < ny.count; ++b) {
          const T* src = xc + cline * ((ny.first + b) + static_cast<std::ptrdiff_t>(cd[1]) * (nz.first + c));
          for (std::ptrdiff_t f = 0; f < cline; ++f) t[f] += w * src[f];
        }
      T* dst = xf + fline * l;
      const char* pin = pinned + static_cast<std::ptrdiff_t>(fd[0]) * l;
      for (int i = 0; i < fd[0]; ++i) {
        if (pin[i]) continue;
        const T* a = t.data() + 3 * (i / 2);
        if (i % 2 == 0) {
          for (int c = 0; c < 3; ++c) dst[3 * i + c] += a[c];
        } else {
          for (int c = 0; c < 3; ++c) dst[3 * i + c] += T(0.5) * (a[c] + a[c + 3]);
        }
      }
    }
  }
}

// bc = Pᵀ rf with rf already zero at the pinned fine nodes (the finest level's residual is
// written that way), so Pᵀ's zero columns need no test here.
template <class T>
void restrict_to_coarse(const std::array<int, 3>& fd, const std::array<int, 3>& cd, const T* rf, T* bc) {
  const std::ptrdiff_t cline = 3 * static_cast<std::ptrdiff_t>(cd[0]);
  const std::ptrdiff_t fline = 3 * static_cast<std::ptrdiff_t>(fd[0]);
  const int lines = cd[1] * cd[2];
#pragma omp parallel if (static_cast <std::ptrdiff_t>(lines) * cd[0] > 2500)
  {
    std::vector<T> s(static_cast<size_t>(fline));  // the fine lines summed in y and z
#pragma omp for schedule(static)
    for (int l = 0; l < lines; ++l) {
      const int cj = l % cd[1], ck = l / cd[1];
      std::fill(s.begin(), s.end(), T(0));
      for (int dz = -1; dz <= 1; ++dz) {
        const int k = 2 * ck + dz;
        if (k < 0 || k >= fd[2]) continue;
        for (int dy = -1; dy <= 1; ++dy) {
          const int j = 2 * cj + dy;
          if (j < 0 || j >= fd[1]) continue;
          const T w = T((dy == 0 ? 1 : 0.5) * (dz == 0 ? 1 : 0.5));
          const T* src = rf + fline * (j + static_cast<std::ptrdiff_t>(fd[1]) * k);
          for (std::ptrdiff_t f = 0; f < fline; ++f) s[f] += w * src[f];
        }
      }
      T* dst = bc + cline * l;
      for (int ci = 0; ci < cd[0]; ++ci)
        for (int c = 0; c < 3; ++c) {
          const int i = 2 * ci;
          T v = i < fd[0] ? s[3 * i + c] : T(0);
          if (i - 1 >= 0) v += T(0.5) * s[3 * (i - 1) + c];
          if (i + 1 < fd[0]) v += T(0.5) * s[3 * (i + 1) + c];
          dst[3 * ci + c] = v;
        }
    }
  }
}

}  // namespace lapis::hair_field::detail
