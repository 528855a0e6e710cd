#include "isoline_samples.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include <Eigen/Eigenvalues>

#include "rotation_fit.h"

namespace lapis::mesh_deform::detail {

std::vector<IsolineSegment> isoline_set_segments(const IsolineBasis& b, const geometry::Faces& F,
                                                 const Eigen::MatrixXd& phi, int set) {
  std::vector<double> levels(static_cast<size_t>(b.isolines));
  for (int j = 0; j < b.isolines; ++j) levels[j] = b.isovalue(j);
  return extract_isolines(b.rest, F, phi.col(field_of_set(b.sets, set)), levels);
}

namespace {

// Every k-th of the isoline's crossed triangles, k the global stride that meets the budget, but
// at least min_per of them: evenly spread over the list (faces in mesh order).
std::vector<int> pick(int size, int stride, int min_per) {
  const int count = std::min(size, std::max(min_per, (size + stride - 1) / stride));
  std::vector<int> idx(static_cast<size_t>(count));
  for (int c = 0; c < count; ++c) idx[c] = static_cast<int>((static_cast<long long>(c) * size) / count);
  return idx;
}

// Isolines without a sample take the fit of the nearest sampled isoline of their set.
std::vector<int> fit_sources(const std::vector<int>& offsets, int sets, int isolines) {
  std::vector<int> src(static_cast<size_t>(sets * isolines), -1);
  for (int i = 0; i < sets; ++i)
    for (int j = 0; j < isolines; ++j)
      for (int d = 0; d < isolines && src[i * isolines + j] < 0; ++d)
        for (int jj : {j - d, j + d})
          if (jj >= 0 && jj < isolines && offsets[i * isolines + jj + 1] > offsets[i * isolines + jj]) {
            src[i * isolines + j] = i * isolines + jj;
            break;
          }
  return src;
}

}  // namespace

IsolineSamples sample_isolines(const IsolineBasis& b, const geometry::Faces& F, const Eigen::MatrixXd& phi, int budget,
                               int min_per) {
  const int m = b.count();
  std::vector<std::vector<IsolineSegment>> per(static_cast<size_t>(m));
  IsolineSamples out;
  for (int i = 0; i < b.sets; ++i)
    for (const IsolineSegment& s : isoline_set_segments(b, F, phi, i))
      if (s.length > 0) per[i * b.isolines + s.level].push_back(s), out.crossed++;
  const int stride = std::max(1, (out.crossed + budget - 1) / std::max(1, budget));

  std::unordered_map<int, int> local;
  auto local_of = [&](int v) {
    auto [it, fresh] = local.try_emplace(v, static_cast<int>(out.vertices.size()));
    if (fresh) out.vertices.push_back(v);
    return it->second;
  };
  out.offsets.push_back(0);
  for (int l = 0; l < m; ++l) {
    for (int k : pick(static_cast<int>(per[l].size()), stride, min_per)) {
      const IsolineSegment& s = per[l][k];
      const Eigen::Vector3i t(local_of(F(s.face, 0)), local_of(F(s.face, 1)), local_of(F(s.face, 2)));
      const Eigen::Vector3d a = b.rest.row(F(s.face, 0)), c = b.rest.row(F(s.face, 1)), d = b.rest.row(F(s.face, 2));
      const Eigen::Vector3d nrm = (c - a).cross(d - a);
      if (!(nrm.norm() > 0)) continue;
      out.tri.push_back(t);
      out.seg.push_back(s);
      out.rest_normal.push_back(nrm.normalized());
    }
    out.offsets.push_back(out.size());
  }
  out.source = fit_sources(out.offsets, b.sets, b.isolines);
  for (int v : out.vertices) {
    out.hom.push_back(b.homogeneous(v));
    for (int i = 0; i < b.sets; ++i) {
      const int s = b.slot(v, i);
      out.lower.push_back(b.lower[s]), out.w0.push_back(b.w0[s]), out.w1.push_back(b.w1[s]);
    }
  }
  return out;
}

geometry::Vertices sample_positions(const IsolineSamples& S, int sets, const TransformBlocks& R) {
  geometry::Vertices X(S.vertices.size(), 3);
  for (size_t k = 0; k < S.vertices.size(); ++k) {
    const size_t s = k * sets;
    X.row(static_cast<Eigen::Index>(k)) = blend(S.hom[k], &S.lower[s], &S.w0[s], &S.w1[s], sets, R).transpose();
  }
  return X;
}

namespace {

Eigen::Matrix3d pseudo_inverse_sym(const Eigen::Matrix3d& B) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(B);
  const Eigen::Vector3d ev = es.eigenvalues();
  const double cut = 1e-9 * std::max(ev.cwiseAbs().maxCoeff(), 1e-300);
  Eigen::Vector3d inv;
  for (int k = 0; k < 3; ++k) inv(k) = std::abs(ev(k)) > cut ? 1.0 / ev(k) : 0.0;
  return es.eigenvectors() * inv.asDiagonal() * es.eigenvectors().transpose();
}

// Segment length on the positions X (sample-local) of triangle t.
double segment_length(const IsolineSegment& s, const Eigen::Vector3i& t, const geometry::Vertices& X) {
  Eigen::Vector3d d = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) d += (s.p.b[k] - s.q.b[k]) * X.row(t(k)).transpose();
  return d.norm();
}

}  // namespace

void fit_isolines(const IsolineSamples& S, const geometry::Vertices& X, NormalFit fit,
                  std::vector<Eigen::Quaterniond>& q, std::vector<Eigen::Matrix3d>& out) {
  const int m = static_cast<int>(S.source.size());
  out.assign(static_cast<size_t>(m), Eigen::Matrix3d::Identity());
  std::vector<Eigen::Matrix3d> own(static_cast<size_t>(m), Eigen::Matrix3d::Identity());
  for (int l = 0; l < m; ++l) {
    if (S.offsets[l + 1] == S.offsets[l]) continue;
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero(), B = Eigen::Matrix3d::Zero();
    double rest_len = 0, len = 0;
    for (int k = S.offsets[l]; k < S.offsets[l + 1]; ++k) {
      const Eigen::Vector3i& t = S.tri[k];
      const Eigen::Vector3d a = X.row(t(0)), c = X.row(t(1)), d = X.row(t(2));
      const Eigen::Vector3d nrm = (c - a).cross(d - a);
      const double area = nrm.norm();
      if (!(area > 0)) continue;
      const double w = S.seg[k].length * S.seg[k].length;  // Eq. 8 weighted by l_k, squared in the normal equations
      A += w * (nrm / area) * S.rest_normal[k].transpose();
      B += w * S.rest_normal[k] * S.rest_normal[k].transpose();
      rest_len += S.seg[k].length;
      if (fit == NormalFit::Similarity) len += segment_length(S.seg[k], t, X);
    }
    if (fit == NormalFit::Paper) {
      own[l] = A * pseudo_inverse_sym(B);
    } else {
      // Parallel normals (a planar isoline) leave the turn about them free; a pull of 10⁻⁶
      // toward the last rotation picks the continuous one and leaves a determined fit alone.
      A += 1e-6 * A.norm() * q[l].toRotationMatrix();
      own[l] = nearest_rotation(A, q[l]);
      if (fit == NormalFit::Similarity && rest_len > 0) own[l] *= len / rest_len;
    }
  }
  for (int l = 0; l < m; ++l)
    if (S.source[l] >= 0) out[l] = own[S.source[l]];
}

}  // namespace lapis::mesh_deform::detail
