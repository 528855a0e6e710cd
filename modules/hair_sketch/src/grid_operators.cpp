#include "lapis/hair_sketch/grid_operators.h"

#include <vector>

namespace lapis::hair_sketch {
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
  return (i > 0) + (i + 1 < g.dims[0]) + (j > 0) + (j + 1 < g.dims[1]) + (k > 0) +
         (k + 1 < g.dims[2]);
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

void apply_normal_operator(const Grid& g, const Eigen::VectorXd& weights, const Field& X,
                           Field& Y) {
  const int n = static_cast<int>(g.num_nodes());
  Field L(n, 3);
  Y.resize(n, 3);
  // L = D X: mean of the neighbours minus the node.
#pragma omp parallel for schedule(static) if (n > 20000)
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i) {
        const int row = g.index(i, j, k);
        Eigen::RowVector3d s = Eigen::RowVector3d::Zero();
        const int c = for_neighbours(g, i, j, k, [&](int col) { s += X.row(col); });
        L.row(row) = s / c - X.row(row);
      }
  // Y = Dᵀ L + diag(w) X: column j of D holds 1/|N(i)| at each neighbour i of j.
#pragma omp parallel for schedule(static) if (n > 20000)
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i) {
        const int row = g.index(i, j, k);
        Eigen::RowVector3d s = -L.row(row) + weights[row] * X.row(row);
        const int sx = 1, sy = g.dims[0], sz = g.dims[0] * g.dims[1];
        if (i > 0) s += L.row(row - sx) / neighbour_count(g, i - 1, j, k);
        if (i + 1 < g.dims[0]) s += L.row(row + sx) / neighbour_count(g, i + 1, j, k);
        if (j > 0) s += L.row(row - sy) / neighbour_count(g, i, j - 1, k);
        if (j + 1 < g.dims[1]) s += L.row(row + sy) / neighbour_count(g, i, j + 1, k);
        if (k > 0) s += L.row(row - sz) / neighbour_count(g, i, j, k - 1);
        if (k + 1 < g.dims[2]) s += L.row(row + sz) / neighbour_count(g, i, j, k + 1);
        Y.row(row) = s;
      }
}

}  // namespace lapis::hair_sketch
