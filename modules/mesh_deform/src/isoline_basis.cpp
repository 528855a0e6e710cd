#include "isoline_basis.h"

#include <algorithm>
#include <cmath>

namespace lapis::mesh_deform::detail {

IsolineBasis make_isoline_basis(const geometry::Vertices& rest, const Eigen::MatrixXd& phi, int isolines) {
  IsolineBasis b;
  const int n = static_cast<int>(rest.rows()), H = static_cast<int>(phi.cols());
  b.sets = H == 2 ? 1 : H;
  b.isolines = isolines;
  b.vertices = n;
  const Eigen::RowVector3d lo = rest.colwise().minCoeff(), hi = rest.colwise().maxCoeff();
  b.center = (0.5 * (lo + hi)).transpose();
  b.scale = std::max((hi - lo).norm(), 1e-300);
  b.rest = (rest.rowwise() - b.center.transpose()) / b.scale;
  b.lower.resize(static_cast<size_t>(n) * b.sets);
  b.w0.resize(b.lower.size());
  b.w1.resize(b.lower.size());
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < b.sets; ++i) {
      const double f = phi(k, field_of_set(b.sets, i));
      // Σ_i φ_i r_i (§4.2); one set for two handles carries the whole transform.
      const IsolineBracket br = isoline_bracket(f, b.sets == 1 ? 1.0 : f, i, isolines);
      const int s = b.slot(k, i);
      b.lower[s] = br.lower;
      b.w0[s] = br.w0;
      b.w1[s] = br.w1;
    }
  return b;
}

TransformBlocks transform_blocks(const solver::DenseMatrix& R) {
  TransformBlocks B(static_cast<size_t>(R.rows() / 4));
  for (size_t l = 0; l < B.size(); ++l) B[l] = R.middleRows<4>(4 * static_cast<Eigen::Index>(l));
  return B;
}

Eigen::Vector3d IsolineBasis::position(int k, const TransformBlocks& R) const {
  const int s = slot(k, 0);
  return blend(homogeneous(k), &lower[s], &w0[s], &w1[s], sets, R);
}

IsolineBracket isoline_bracket(double f, double weight, int set, int isolines) {
  const double steps = isolines - 1;
  const int j = std::clamp(static_cast<int>(std::floor(f * steps)), 0, isolines - 2);
  const double alpha = f * steps - j;
  return {set * isolines + j, weight * (1 - alpha), weight * alpha};
}

}  // namespace lapis::mesh_deform::detail
