#include "edge_cell_sums.h"

#include "stencil.h"

namespace lapis::mesh_deform::detail {

EdgeCellSums::EdgeCellSums(const Stencil& s, std::vector<double> u, const geometry::Vertices& rest)
    : s_(s), u_(std::move(u)), rest_(rest) {
  const int n = s.size();
  weight_.assign(static_cast<size_t>(n), 0.0);
  rest_sum_.assign(static_cast<size_t>(n), Eigen::Vector3d::Zero());
  sum_.assign(static_cast<size_t>(n), Eigen::Vector3d::Zero());
  outer_.assign(static_cast<size_t>(n), Eigen::Matrix3d::Zero());
  for (int i = 0; i < n; ++i)
    for (int k = s.offsets[i]; k < s.offsets[i + 1]; ++k) {
      weight_[static_cast<size_t>(i)] += u_[k];
      rest_sum_[static_cast<size_t>(i)] += u_[k] * (rest.row(s.nbr[k]) - rest.row(i)).transpose();
    }
}

void EdgeCellSums::update(const geometry::Vertices& X) {
  for_vertices(static_cast<size_t>(s_.size()), [&](std::ptrdiff_t i) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();
    for (int k = s_.offsets[i]; k < s_.offsets[i + 1]; ++k) {
      const Eigen::Vector3d x = u_[k] * (X.row(s_.nbr[k]) - X.row(i)).transpose();
      sum += x;
      outer.noalias() += x * (rest_.row(s_.nbr[k]) - rest_.row(i));
    }
    sum_[static_cast<size_t>(i)] = sum;
    outer_[static_cast<size_t>(i)] = outer;
  });
}

// Σ_k u (x̃_a − x̃_k)(ṽ_a − ṽ_k)ᵀ with x̃ = x − x_c: W x̃_a ṽ_aᵀ − x̃_a (Σ u ṽ_k)ᵀ − (Σ u x̃_k) ṽ_aᵀ + Σ u x̃_k ṽ_kᵀ.
Eigen::Matrix3d EdgeCellSums::fan(int c, int a, const geometry::Vertices& X) const {
  const Eigen::Vector3d xa = (X.row(a) - X.row(c)).transpose(), va = (rest_.row(a) - rest_.row(c)).transpose();
  const auto ci = static_cast<size_t>(c);
  return (weight_[ci] * xa - sum_[ci]) * va.transpose() - xa * rest_sum_[ci].transpose() + outer_[ci];
}

Eigen::Matrix3d EdgeCellSums::fans(int i, int j, const geometry::Vertices& X) const {
  return fan(i, j, X) + fan(j, i, X);
}

}  // namespace lapis::mesh_deform::detail
