#include "salient_system.h"

#include "lapis/geometry/laplacian.h"

namespace lapis::mesh_deform::detail {
namespace {

using Sparse = solver::SparseMatrix;

// w_i of Eq. 2: |F_i| / mean |F| ("its size", §3.2) or 1, times the user's scale.
std::vector<double> feature_weights(const std::vector<Feature>& features, const SalientOptions& o) {
  double mean = 0;
  for (const auto& f : features) mean += static_cast<double>(f.size());
  mean /= std::max<double>(1, static_cast<double>(features.size()));
  std::vector<double> w;
  for (const auto& f : features)
    w.push_back(o.feature_weight_scale *
                (o.feature_weight == FeatureWeight::Size ? static_cast<double>(f.size()) / mean : 1.0));
  return w;
}

// Σ_i w_i Σ_{j∈F_i} (C_j − c̄_i)ᵀ(C_j − c̄_i) = Σ_i w_i (C_Fᵀ C_F − |F_i| c̄_i c̄_iᵀ), c̄_i the mean row:
// Eq. 1 with c′_i = the mean of C_j Z, so no centroid unknown is needed.
Sparse feature_normal(const SalientSystem& s) {
  const Eigen::Index n = s.C.rows(), cols = s.C.cols();
  Eigen::VectorXd d = Eigen::VectorXd::Zero(n);
  Sparse centred(cols, cols);
  for (size_t i = 0; i < s.features.size(); ++i) {
    const Feature& f = s.features[i];
    Eigen::SparseVector<double> mean(cols);
    for (int v : f) {
      d[v] = s.weight[i];
      mean += Eigen::SparseVector<double>(s.Ct.col(v));
    }
    mean /= static_cast<double>(f.size());
    const Sparse m(mean);
    centred += (s.weight[i] * static_cast<double>(f.size())) * Sparse(m * m.transpose());
  }
  return Sparse(s.Ct * d.asDiagonal() * s.C) - centred;
}

// α (D L C)ᵀ (D L C), D selecting the vertices outside the features (Eq. 3).
Sparse detail_normal(const SalientSystem& s, double alpha) {
  Eigen::VectorXd d = Eigen::VectorXd::Zero(s.L.rows());
  for (int v : s.detail_vertices) d[v] = 1;
  const Sparse LC = Sparse(d.asDiagonal() * s.L) * s.C;
  return alpha * Sparse(Sparse(LC.transpose()) * LC);
}

Sparse gram(const Sparse& B, double weight) { return weight * Sparse(Sparse(B.transpose()) * B); }

}  // namespace

SalientSystem assemble_salient_system(const TriMesh& mesh, std::vector<Feature> features, const geometry::TetMesh& tets,
                                      Sparse C, const SalientOptions& o) {
  SalientSystem s;
  s.C = std::move(C);
  s.Ct = s.C.transpose();
  s.L = geometry::cotan_laplacian(mesh);
  s.delta = s.L * mesh.V;
  std::vector<char> in_feature(static_cast<size_t>(mesh.num_vertices()), 0);
  for (const auto& f : features)
    for (int v : f) in_feature[v] = 1;
  for (int v = 0; v < mesh.num_vertices(); ++v)
    if (!in_feature[v]) s.detail_vertices.push_back(v);
  s.features = std::move(features);
  s.weight = feature_weights(s.features, o);
  for (const auto& f : s.features) {
    Vertices q(static_cast<Eigen::Index>(f.size()), 3);
    for (size_t j = 0; j < f.size(); ++j) q.row(static_cast<Eigen::Index>(j)) = mesh.V.row(f[j]);
    q.rowwise() -= q.colwise().mean();
    s.offsets.push_back(std::move(q));
  }
  s.normal = feature_normal(s) + detail_normal(s, o.alpha) + gram(discontinuity_rows(tets), o.gamma) +
             gram(vibration_rows(tets), o.lambda);
  return s;
}

Sparse handle_normal(const Sparse& C, const std::vector<int>& vertices, double beta) {
  Eigen::VectorXd d = Eigen::VectorXd::Zero(C.rows());
  for (int v : vertices) d[v] = beta;
  return Sparse(Sparse(C.transpose()) * d.asDiagonal() * C);
}

}  // namespace lapis::mesh_deform::detail
