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
  const double steps = isolines - 1;
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < b.sets; ++i) {
      const double f = phi(k, field_of_set(b.sets, i));
      const double weight = b.sets == 1 ? 1.0 : f;  // Σ_i φ_i r_i; one set carries the whole transform
      const int j = std::clamp(static_cast<int>(std::floor(f * steps)), 0, isolines - 2);
      const double alpha = f * steps - j;  // §4.2: (φ − s_j) / (s_{j+1} − s_j)
      const int s = b.slot(k, i);
      b.lower[s] = i * isolines + j;
      b.w0[s] = weight * (1 - alpha);
      b.w1[s] = weight * alpha;
    }
  return b;
}

}  // namespace lapis::mesh_deform::detail
