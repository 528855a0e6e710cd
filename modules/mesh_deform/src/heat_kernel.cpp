#include "lapis/mesh_deform/heat_kernel.h"

#include <cmath>
#include <string>

#include "lapis/geometry/laplacian.h"

namespace lapis::mesh_deform {

Eigen::VectorXd heat_kernel_times(const Eigen::VectorXd& values, int count, double truncation) {
  constexpr const char* fn = "mesh_deform::heat_kernel_times()";
  if (values.size() < 2 || !(values[1] > 0))
    throw InvalidArgument(std::string(fn) +
                          ": expected at least two eigenvalues with lambda_2 > 0 (is the mesh "
                          "connected?)");
  if (count < 1 || !(truncation > 0 && truncation < 1))
    throw InvalidArgument(std::string(fn) + ": expected count >= 1 and truncation in (0, 1)");
  const double c = -std::log(truncation);
  const double lo = std::log(c / values[values.size() - 1]), hi = std::log(c / values[1]);
  Eigen::VectorXd t(count);
  for (int i = 0; i < count; ++i) t[i] = std::exp(count == 1 ? lo : lo + (hi - lo) * i / (count - 1));
  return t;
}

// Each weight e^{−λ_i t} is divided by e^{−λ_1 t} before summing: at the largest times the
// raw weights of a large mesh's λ would underflow together, the ratios do not.
Eigen::MatrixXd scaled_heat_kernel_signature(const solver::Eigenpairs& spectrum, const Eigen::VectorXd& times) {
  const Eigen::VectorXd& lambda = spectrum.values;
  const Eigen::MatrixXd sq = spectrum.vectors.array().square().matrix();
  Eigen::MatrixXd h(sq.rows(), times.size());
  for (Eigen::Index c = 0; c < times.size(); ++c) {
    const Eigen::VectorXd w = (-(lambda.array() - lambda[0]) * times[c]).exp().matrix();
    h.col(c) = sq * w / w.sum();
  }
  return h;
}

Eigen::VectorXd hks_saliency(const solver::Eigenpairs& spectrum, const Eigen::VectorXd& times, double area) {
  const Eigen::MatrixXd h = scaled_heat_kernel_signature(spectrum, times);
  return (area * h.rowwise().mean()).array() - 1.0;
}

solver::Eigenpairs laplacian_spectrum(const geometry::TriMesh& mesh, int k, const solver::EigenOptions& options) {
  geometry::require_valid(mesh, {}, "mesh_deform::laplacian_spectrum()");
  const solver::SparseMatrix K = -geometry::cotan_laplacian(mesh);
  const solver::SparseMatrix M = geometry::mass_matrix(mesh, geometry::MassType::Voronoi);
  return solver::smallest_eigenpairs(K, M, k, options);
}

}  // namespace lapis::mesh_deform
