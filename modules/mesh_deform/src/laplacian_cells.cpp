#include "laplacian_cells.h"

#include "sparse_rows.h"
#include "stencil.h"

namespace lapis::mesh_deform::detail {

LaplacianCells vertex_cells(const Stencil& s) {
  LaplacianCells cells;
  cells.c = 1;
  cells.offsets = s.offsets;
  cells.q = s.nbr;
  cells.w = s.w;
  cells.p.resize(s.nbr.size());
  for (int i = 0; i < s.size(); ++i)
    for (int k = s.offsets[i]; k < s.offsets[i + 1]; ++k) cells.p[k] = i;
  return cells;
}

LaplacianCells edge_cells(const Stencil& s, LaplacianWeights weights) {
  LaplacianCells cells;
  cells.c = 0.5;
  cells.offsets.push_back(0);
  // The edges in the stencil's order (i ascending, then j), so nodes of nearby vertices are
  // near in memory whenever the vertices are.
  for (int i = 0; i < s.size(); ++i)
    for (int ij = s.offsets[i]; ij < s.offsets[i + 1]; ++ij) {
      const int j = s.nbr[ij];
      if (j < i) continue;
      const double uniform = 1.0 / (s.valence(i) + s.valence(j) - 2);
      // Edges (a, k) at the shared end a: m_ij − m_ak = (v_b − v_k)/2, b the other end.
      auto add_fan = [&](int a, int b) {
        for (int k = s.offsets[a]; k < s.offsets[a + 1]; ++k) {
          if (s.nbr[k] == b) continue;
          cells.p.push_back(b);
          cells.q.push_back(s.nbr[k]);
          cells.w.push_back(weights == LaplacianWeights::Uniform ? uniform : s.w[k]);
        }
      };
      add_fan(i, j);
      add_fan(j, i);
      cells.ends.push_back({i, j});
      cells.offsets.push_back(static_cast<int>(cells.p.size()));
    }
  return cells;
}

solver::SparseMatrix laplacian_rows(const LaplacianCells& cells, const std::vector<int>& nodes, int num_vertices) {
  SparseRows D(num_vertices);
  for (int a : nodes) {
    D.begin_row();
    for (int k = cells.offsets[a]; k < cells.offsets[a + 1]; ++k) {
      D.add(cells.p[k], cells.c * cells.w[k]);
      D.add(cells.q[k], -cells.c * cells.w[k]);
    }
  }
  return D.matrix();
}

geometry::Vertices laplacian_vectors(const LaplacianCells& cells, const geometry::Vertices& P) {
  const int n = cells.num_nodes();
  geometry::Vertices D(n, 3);
  for_vertices(static_cast<size_t>(n), [&](std::ptrdiff_t a) {
    Eigen::RowVector3d d = Eigen::RowVector3d::Zero();
    for (int k = cells.offsets[a]; k < cells.offsets[a + 1]; ++k)
      d += cells.w[k] * (P.row(cells.p[k]) - P.row(cells.q[k]));
    D.row(a) = cells.c * d;
  });
  return D;
}

}  // namespace lapis::mesh_deform::detail
