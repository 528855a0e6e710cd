// Compressed adjacency lists (offsets + items) shared by validation and Connectivity:
// one allocation per list instead of a std::vector per vertex, which matters at 1M vertices.
#pragma once

#include <span>
#include <vector>

#include "lapis/geometry/tri_mesh.h"

namespace lapis::geometry::detail {

struct Csr {
  std::vector<int> offsets;  // size n + 1
  std::vector<int> items;
  std::span<const int> operator[](int i) const {
    return {items.data() + offsets[i], static_cast<size_t>(offsets[i + 1] - offsets[i])};
  }
  int size() const { return static_cast<int>(offsets.size()) - 1; }
};

// Faces around each vertex, in ascending face order. Every index of F must be in range.
inline Csr vertex_face_csr(const Faces& F, int num_vertices) {
  Csr csr;
  csr.offsets.assign(num_vertices + 1, 0);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) ++csr.offsets[F(f, k) + 1];
  for (int v = 0; v < num_vertices; ++v) csr.offsets[v + 1] += csr.offsets[v];
  csr.items.resize(csr.offsets[num_vertices]);
  std::vector<int> fill(csr.offsets.begin(), csr.offsets.end() - 1);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int v = F(f, k);
      // A face with a repeated index is listed once per vertex.
      if (k > 0 && F(f, 0) == v) continue;
      if (k > 1 && F(f, 1) == v) continue;
      csr.items[fill[v]++] = static_cast<int>(f);
    }
  // Shrink the gaps left by repeated indices (rare: degenerate faces only).
  int out = 0;
  for (int v = 0; v < num_vertices; ++v) {
    const int begin = csr.offsets[v], end = fill[v];
    csr.offsets[v] = out;
    for (int i = begin; i < end; ++i) csr.items[out++] = csr.items[i];
  }
  csr.offsets[num_vertices] = out;
  csr.items.resize(out);
  return csr;
}

}  // namespace lapis::geometry::detail
