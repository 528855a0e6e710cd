// Test and benchmark matrices for the solver layer: the uniform 6-neighbour Laplacian D of
// an N×N×N grid, the hair-sketching normal matrix DᵀD + ω² Σ_{i∈C} e_i e_iᵀ (thesis §4.4.1),
// and random SPD matrices.
#pragma once

#include <random>
#include <vector>

#include "lapis/solver/types.h"

namespace lapis::solver::testing {

// Uniform graph Laplacian of the N³ grid (row i: Σ_j (x_j − x_i) over face neighbours).
inline SparseMatrix grid_laplacian_3d(int N) {
  const int n = N * N * N;
  auto id = [N](int x, int y, int z) { return (z * N + y) * N + x; };
  std::vector<Eigen::Triplet<double, int>> t;
  t.reserve(static_cast<size_t>(n) * 7);
  for (int z = 0; z < N; ++z)
    for (int y = 0; y < N; ++y)
      for (int x = 0; x < N; ++x) {
        const int i = id(x, y, z);
        int deg = 0;
        const int nb[6][3] = {{x - 1, y, z}, {x + 1, y, z}, {x, y - 1, z}, {x, y + 1, z}, {x, y, z - 1}, {x, y, z + 1}};
        for (const auto& q : nb) {
          if (q[0] < 0 || q[1] < 0 || q[2] < 0 || q[0] >= N || q[1] >= N || q[2] >= N) continue;
          t.emplace_back(i, id(q[0], q[1], q[2]), 1.0);
          ++deg;
        }
        t.emplace_back(i, i, -static_cast<double>(deg));
      }
  SparseMatrix D(n, n);
  D.setFromTriplets(t.begin(), t.end());
  return D;
}

// Every `stride`-th node, offset by `offset`: a spread set of constrained nodes.
inline std::vector<int> spread_nodes(int n, int count, int offset = 0) {
  std::vector<int> out;
  const int stride = std::max(1, n / std::max(1, count));
  for (int i = offset % stride; i < n && static_cast<int>(out.size()) < count; i += stride) out.push_back(i);
  return out;
}

// DᵀD + ω² Σ_{i∈C} e_i e_iᵀ.
inline SparseMatrix hair_normal_matrix(int N, const std::vector<int>& constrained, double omega = 100) {
  const SparseMatrix D = grid_laplacian_3d(N);
  SparseMatrix A = SparseMatrix(D.transpose()) * D;
  for (int i : constrained) A.coeffRef(i, i) += omega * omega;
  A.makeCompressed();
  return A;
}

// A random sparse SPD matrix: B Bᵀ + n·I-ish diagonal dominance, with ~density·n² entries.
inline SparseMatrix random_spd(int n, double density, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_int_distribution<int> pick(0, n - 1);
  std::vector<Eigen::Triplet<double, int>> t;
  const int m = std::max(1, static_cast<int>(density * n * n / 2));
  for (int k = 0; k < m; ++k) {
    const int i = pick(rng), j = pick(rng);
    const double v = u(rng);
    t.emplace_back(i, j, v);
    t.emplace_back(j, i, v);
  }
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  // Gershgorin: a diagonal above each row's absolute sum makes A SPD.
  for (int i = 0; i < n; ++i) {
    double s = 0;
    for (SparseMatrix::InnerIterator it(A, i); it; ++it)
      if (it.row() != i) s += std::abs(it.value());
    A.coeffRef(i, i) += s + 0.5 + std::abs(u(rng));
  }
  A.makeCompressed();
  return A;
}

}  // namespace lapis::solver::testing
