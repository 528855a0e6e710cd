#include "lapis/mesh_deform/salient_deformer.h"

#include <chrono>
#include <cmath>

#include "handle_rotation_blend.h"
#include "lapis/core/parallel_for.h"
#include "lapis/geometry/polar.h"
#include "lapis/mesh_deform/feature_rigidity.h"
#include "lapis/solver/cholesky.h"
#include "rotation_fit.h"
#include "salient_system.h"
#include "stencil.h"

namespace lapis::mesh_deform {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

double diagonal(const Vertices& V) { return (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm(); }

}  // namespace

struct SalientDeformer::Model {
  std::vector<Feature> features;
  Eigen::VectorXd saliency;
  geometry::TetMesh tets;
  detail::SalientSystem system;
  // Non-negative cotangent weights for the shape-matching covariances of Eq. 3's R_i (a
  // negative weight would reward misfit); δ itself keeps the signed cotangents.
  detail::Stencil stencil;
};

struct SalientDeformer::Frame {
  solver::Cholesky chol;
  std::vector<int> constrained;
  std::vector<Eigen::Matrix3d> R;     // #V: Eq. 3's R_i (used at detail vertices)
  std::vector<Eigen::Quaterniond> q;  // the same, each fit's starting guess
  std::vector<Eigen::Matrix3d> R_feature;
  // #V by #region handles: the subspace's scalar field of each region handle (1 on it, 0 on
  // the other constrained vertices), with each feature's mean; weights of a cold start.
  solver::DenseMatrix handle_fields, feature_fields;
  solver::DenseMatrix Z;  // subspace coefficients of the last solve
  Vertices P;             // C Z
  bool have_previous = false;
};

SalientDeformer::SalientDeformer(TriMesh mesh, SalientOptions options) : Deformer(std::move(mesh)) {
  set_options(options);
}
SalientDeformer::~SalientDeformer() = default;

void SalientDeformer::set_options(const SalientOptions& o) {
  auto nonneg = [](double x) { return std::isfinite(x) && x >= 0; };
  if (!nonneg(o.alpha) || !nonneg(o.beta) || !nonneg(o.gamma) || !nonneg(o.lambda) || !(o.alpha > 0) || !(o.beta > 0) ||
      !(o.gamma + o.lambda > 0) || !nonneg(o.feature_weight_scale) || o.iterations < 1 || o.subspace_vertices < 8)
    throw InvalidArgument(
        "mesh_deform::SalientDeformer::set_options(): expected finite weights >= 0 with alpha, beta and gamma + "
        "lambda > 0, iterations >= 1 and subspace_vertices >= 8");
  if (!(o.detection == options_.detection)) detection_.reset();
  options_ = o;
  model_.reset();
  mark_dirty();
}

void SalientDeformer::set_detection(SalientFeatures detection) {
  if (detection.saliency.size() != mesh_.num_vertices())
    throw InvalidArgument(
        "mesh_deform::SalientDeformer::set_detection(): " + std::to_string(detection.saliency.size()) +
        " saliency values for " + std::to_string(mesh_.num_vertices()) + " vertices");
  detection_ = std::move(detection);
  model_.reset();
  mark_dirty();
}

void SalientDeformer::set_features(std::vector<Feature> features) {
  user_features_ = std::move(features);
  model_.reset();
  mark_dirty();
}

void SalientDeformer::set_subspace(geometry::TetMesh tets) {
  given_subspace_ = std::move(tets);
  model_.reset();
  mark_dirty();
}

const std::vector<Feature>& SalientDeformer::features() const {
  static const std::vector<Feature> none;
  return model_ ? model_->features : none;
}
const Eigen::VectorXd& SalientDeformer::saliency() const {
  static const Eigen::VectorXd none;
  return model_ ? model_->saliency : none;
}
const geometry::TetMesh& SalientDeformer::subspace() const {
  static const geometry::TetMesh none;
  return model_ ? model_->tets : none;
}

void SalientDeformer::reset_warm_start() {
  if (frame_) frame_->have_previous = false;
}

// Everything that does not depend on the selection: detection (§3.1), the subspace (§4.1),
// its coordinates (§4.2) and the selection-free part of system (11).
void SalientDeformer::build_model() {
  constexpr const char* fn = "mesh_deform::SalientDeformer::precompute()";
  auto m = std::make_unique<Model>();
  const int n = mesh_.num_vertices();
  auto t0 = Clock::now();
  std::vector<Feature> detected;
  if (options_.detect_features) {
    if (!detection_) detection_ = detect_salient_features(mesh_, options_.detection);
    m->saliency = detection_->saliency;
    detected = detection_->features;
    report_.detection = detection_->report;
  }
  m->features =
      user_features_.empty() ? detected : combine_features(detected, user_features_, options_.user_features, n);
  report_.detection_ms = ms_since(t0);

  t0 = Clock::now();
  if (given_subspace_) {
    geometry::require_valid_tets(*given_subspace_, fn);
    m->tets = *given_subspace_;
  } else {
    m->tets = geometry::lattice_enclosure(mesh_, options_.subspace_vertices);
  }
  report_.subspace_ms = ms_since(t0);

  t0 = Clock::now();
  SubspaceEmbedding e = embed_in_subspace(m->tets, mesh_.V);
  report_.strays = e.strays;
  report_.embedding_ms = ms_since(t0);

  m->stencil = detail::make_stencil(mesh_.V, mesh_.F, LaplacianWeights::Cotangent, detail::ObtuseAngles::ClampToZero);
  t0 = Clock::now();
  m->system = detail::assemble_salient_system(mesh_, m->features, m->tets, std::move(e.C), options_);
  report_.system_ms = ms_since(t0);
  report_.features = static_cast<int>(m->features.size());
  report_.feature_vertices = 0;
  for (const auto& f : m->features) report_.feature_vertices += static_cast<int>(f.size());
  report_.subspace_vertices = m->tets.num_vertices();
  report_.tets = m->tets.num_tets();
  report_.unknowns = 4 * m->tets.num_vertices();
  model_ = std::move(m);
}

void SalientDeformer::setup(const Layout& layout) {
  if (!model_) build_model();
  const auto t0 = Clock::now();
  auto f = std::make_unique<Frame>();
  f->constrained = layout.constrained;
  const solver::SparseMatrix N =
      model_->system.normal + detail::handle_normal(model_->system.C, f->constrained, options_.beta);
  const auto tf = Clock::now();
  try {
    f->chol.compute(N);
  } catch (const NotPositiveDefinite& e) {
    throw NotPositiveDefinite(std::string("mesh_deform::SalientDeformer::precompute(): the subspace system is not "
                                          "positive definite (do the handles and the fixed region pin an affine "
                                          "map?): ") +
                                  e.what(),
                              -1);
  }
  report_.factorize_ms = ms_since(tf);
  const int n = mesh_.num_vertices();
  f->R.assign(static_cast<size_t>(n), Eigen::Matrix3d::Identity());
  f->q.assign(static_cast<size_t>(n), Eigen::Quaterniond::Identity());
  f->R_feature.assign(model_->features.size(), Eigen::Matrix3d::Identity());
  build_handle_fields(*f, layout);
  report_.precompute_ms = report_.system_ms + ms_since(t0);
  frame_ = std::move(f);
}

// The cold start's weights: system (11) with zero detail and rigid offsets, solved for one
// scalar per vertex with the handle rows pulling handle h's vertices to 1 and every other
// constrained vertex to 0. The fields sum to one wherever the fixed region is empty (the
// subspace reproduces constants) and are nearly constant on each feature (Eq. 1 pulls a
// feature's values to their mean). One solve of #region-handle right-hand sides.
void SalientDeformer::build_handle_fields(Frame& f, const Layout& layout) const {
  const detail::SalientSystem& s = model_->system;
  const int n = mesh_.num_vertices(), nh = layout.num_region_handles;
  solver::DenseMatrix pull = solver::DenseMatrix::Zero(n, nh);
  for (int v : f.constrained)
    if (layout.role[v] == VertexRole::RegionHandle) pull(v, layout.handle_of[v]) = options_.beta;
  f.handle_fields = s.C * f.chol.solve(s.Ct * pull);
  f.feature_fields = solver::DenseMatrix::Zero(static_cast<Eigen::Index>(s.features.size()), nh);
  for (size_t i = 0; i < s.features.size(); ++i) {
    for (int v : s.features[i]) f.feature_fields.row(static_cast<Eigen::Index>(i)) += f.handle_fields.row(v);
    f.feature_fields.row(static_cast<Eigen::Index>(i)) /= static_cast<double>(s.features[i].size());
  }
}

// Rotations of a frame without a previous result (SalientOptions::cold_start).
void SalientDeformer::start_cold(Frame& f, const HandleTransforms& transforms) const {
  if (options_.cold_start == ColdStart::Identity) {
    std::fill(f.R.begin(), f.R.end(), Eigen::Matrix3d::Identity());
    std::fill(f.q.begin(), f.q.end(), Eigen::Quaterniond::Identity());
    std::fill(f.R_feature.begin(), f.R_feature.end(), Eigen::Matrix3d::Identity());
    return;
  }
  const std::vector<Eigen::Vector3d> r = detail::region_rotation_vectors(transforms);
  detail::for_vertices(f.R.size(), [&](std::ptrdiff_t i) {
    f.q[i] = detail::blended_rotation(f.handle_fields.row(i), r);
    f.R[i] = f.q[i].toRotationMatrix();
  });
  for (size_t i = 0; i < f.R_feature.size(); ++i)
    f.R_feature[i] = detail::blended_rotation(f.feature_fields.row(static_cast<Eigen::Index>(i)), r).toRotationMatrix();
}

namespace {

// Eq. 1's R_i by Kabsch: A = Σ_j (p′_j − c′)(p_j − c)ᵀ = Σ_j p′_j q_jᵀ, as Σ_j q_j = 0.
void fit_feature_rotations(const detail::SalientSystem& s, const Vertices& P, std::vector<Eigen::Matrix3d>& R) {
  for (size_t i = 0; i < s.features.size(); ++i) {
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
    const Feature& f = s.features[i];
    for (size_t j = 0; j < f.size(); ++j) A += P.row(f[j]).transpose() * s.offsets[i].row(static_cast<Eigen::Index>(j));
    R[i] = geometry::polar_rotation(A);
  }
}

// Eq. 3's R_i by shape matching over the 1-ring (§3.3), ARAP's cotangent-weighted covariance.
void fit_detail_rotations(const detail::SalientSystem& s, const detail::Stencil& st, const Vertices& rest,
                          const Vertices& P, std::vector<Eigen::Matrix3d>& R, std::vector<Eigen::Quaterniond>& q) {
  detail::for_vertices(s.detail_vertices.size(), [&](std::ptrdiff_t k) {
    const int i = s.detail_vertices[static_cast<size_t>(k)];
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
    for (int e = st.offsets[i]; e < st.offsets[i + 1]; ++e) {
      const int j = st.nbr[e];
      A.noalias() += st.w[e] * (P.row(i) - P.row(j)).transpose() * (rest.row(i) - rest.row(j));
    }
    R[i] = detail::nearest_rotation(A, q[i]);
  });
}

// Y with rhs = Cᵀ Y: w_i R_i q_j at feature vertices (Eq. 1–2), α L (R_i δ_i) over the detail
// vertices (Eq. 3; L is symmetric), plus the frame's handle part.
Vertices right_hand_side(const detail::SalientSystem& s, const std::vector<Eigen::Matrix3d>& R_feature,
                         const std::vector<Eigen::Matrix3d>& R, const Vertices& handle_part, double alpha) {
  Vertices turned = Vertices::Zero(s.delta.rows(), 3);
  detail::for_vertices(s.detail_vertices.size(), [&](std::ptrdiff_t k) {
    const int i = s.detail_vertices[static_cast<size_t>(k)];
    turned.row(i) = (R[i] * s.delta.row(i).transpose()).transpose();
  });
  Vertices Y = handle_part + alpha * (s.L * turned);
  for (size_t i = 0; i < s.features.size(); ++i)
    for (size_t j = 0; j < s.features[i].size(); ++j)
      Y.row(s.features[i][j]) +=
          s.weight[i] * (R_feature[i] * s.offsets[i].row(static_cast<Eigen::Index>(j)).transpose()).transpose();
  return Y;
}

}  // namespace

void SalientDeformer::solve(const HandleTransforms& transforms, const Vertices& targets, Vertices& out) {
  const auto t_frame = Clock::now();
  Frame& f = *frame_;
  const detail::SalientSystem& s = model_->system;
  if (!(options_.warm_start && f.have_previous)) start_cold(f, transforms);
  Vertices handle_part = Vertices::Zero(targets.rows(), 3);
  for (int v : f.constrained) handle_part.row(v) = options_.beta * targets.row(v);
  Vertices previous = f.have_previous ? f.P : mesh_.V;
  const double diag = diagonal(mesh_.V);
  double rot_ms = 0, solve_ms = 0, interp_ms = 0;
  for (int it = 0; it < options_.iterations; ++it) {
    auto t0 = Clock::now();
    const solver::DenseMatrix rhs = s.Ct * right_hand_side(s, f.R_feature, f.R, handle_part, options_.alpha);
    rot_ms += ms_since(t0);
    t0 = Clock::now();
    f.Z = f.chol.solve(rhs);
    solve_ms += ms_since(t0);
    t0 = Clock::now();
    f.P = s.C * f.Z;
    interp_ms += ms_since(t0);
    report_.last_change = (f.P - previous).rowwise().norm().maxCoeff() / diag;
    previous = f.P;
    t0 = Clock::now();
    fit_feature_rotations(s, f.P, f.R_feature);
    fit_detail_rotations(s, model_->stencil, mesh_.V, f.P, f.R, f.q);
    rot_ms += ms_since(t0);
  }
  f.have_previous = true;
  report_.handle_residual = 0;
  for (int v : f.constrained)
    report_.handle_residual = std::max(report_.handle_residual, (f.P.row(v) - targets.row(v)).norm());
  const Layout& L = layout();
  for (int v = 0; v < mesh_.num_vertices(); ++v)
    if (L.role[v] != VertexRole::Fixed) out.row(v) = f.P.row(v);
  report_.feature_residual = 0;
  for (const Feature& feature : s.features)
    report_.feature_residual = std::max(report_.feature_residual, feature_rigidity_residual(mesh_.V, f.P, feature));
  report_.iterations = options_.iterations;
  report_.rotations_ms = rot_ms;
  report_.solves_ms = solve_ms;
  report_.interpolation_ms = interp_ms;
  report_.frame_ms = ms_since(t_frame);
}

}  // namespace lapis::mesh_deform
