#include "lapis/hair_field/grid_operators.h"

#include <vector>

#include "grid_stencil.h"

namespace lapis::hair_field {
namespace {

// Calls f(j) for each grid neighbour j of (i, j, k); returns their count.
template <class F>
inline int for_neighbours(const Grid& g, int i, int j, int k, F&& f) {
  const int sx = 1, sy = g.dims[0], sz = g.dims[0] * g.dims[1];
  const int n = g.index(i, j, k);
  int c = 0;
  if (i > 0) f(n - sx), ++c;
  if (i + 1 < g.dims[0]) f(n + sx), ++c;
  if (j > 0) f(n - sy), ++c;
  if (j + 1 < g.dims[1]) f(n + sy), ++c;
  if (k > 0) f(n - sz), ++c;
  if (k + 1 < g.dims[2]) f(n + sz), ++c;
  return c;
}

inline int neighbour_count(const Grid& g, int i, int j, int k) {
  return (i > 0) + (i + 1 < g.dims[0]) + (j > 0) + (j + 1 < g.dims[1]) + (k > 0) + (k + 1 < g.dims[2]);
}

}  // namespace

SparseMatrix laplacian_matrix(const Grid& g) {
  const int n = static_cast<int>(g.num_nodes());
  std::vector<Eigen::Triplet<double, int>> t;
  t.reserve(static_cast<size_t>(n) * 7);
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i) {
        const int row = g.index(i, j, k);
        const double inv = 1.0 / neighbour_count(g, i, j, k);
        t.emplace_back(row, row, -1.0);
        for_neighbours(g, i, j, k, [&](int col) { t.emplace_back(row, col, inv); });
      }
  SparseMatrix D(n, n);
  D.setFromTriplets(t.begin(), t.end());
  return D;
}

SparseMatrix normal_matrix(const Grid& grid, const Eigen::VectorXd& weights) {
  const SparseMatrix D = laplacian_matrix(grid);
  SparseMatrix A = SparseMatrix(D.transpose()) * D;
  for (int i = 0; i < A.rows(); ++i) A.coeffRef(i, i) += weights[i];
  A.makeCompressed();
  return A;
}

void apply_normal_operator(const Grid& g, const Eigen::VectorXd& weights, const Field& X, Field& Y) {
  Y.resize(X.rows(), 3);
  detail::StencilScratch<double> buffers;
  detail::normal_operator(g.dims, weights.data(), X.data(), Y.data(), false, buffers);
}

}  // namespace lapis::hair_field
