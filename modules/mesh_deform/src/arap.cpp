#include "lapis/mesh_deform/arap.h"

#include <chrono>
#include <cmath>

#include "lapis/solver/cholesky.h"
#include "rotation_fit.h"
#include "stencil.h"

namespace lapis::mesh_deform {
namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

// The global step solves L_ff d_f = b_f − (L V)_f − L_fc d_c for displacements d from the
// rest mesh, so that identity rotations give an exactly zero right-hand side.
struct ArapDeformer::Impl {
  detail::Stencil s;                 // cotangent weights, neighbour lists in contiguous arrays
  std::vector<int> free;             // ascending
  std::vector<int> local;            // vertex -> index among free, -1 for constrained
  std::vector<int> fitted;           // vertices whose rotation a free vertex's row reads
  solver::Cholesky chol;
  std::vector<Eigen::Vector3d> we;   // per stencil entry: w_ij (v_i − v_j), contiguous
  std::vector<double> rest_sq;       // per vertex: Σ_j w_ij ‖v_i − v_j‖²
  std::vector<Eigen::Matrix3d> R;    // #V rotations
  std::vector<Eigen::Quaterniond> q; // the same rotations, each fit's start in the next iteration
  Vertices previous;                 // last frame's result
  bool have_previous = false;
};

ArapDeformer::ArapDeformer(TriMesh mesh, ArapOptions options) : Deformer(std::move(mesh)) { set_options(options); }
ArapDeformer::~ArapDeformer() = default;

void ArapDeformer::set_options(const ArapOptions& options) {
  if (options.max_iterations < 1 || !(options.tolerance >= 0))
    throw InvalidArgument("mesh_deform::ArapDeformer::set_options(): max_iterations must be >= 1 and tolerance >= 0");
  options_ = options;
}

void ArapDeformer::reset_warm_start() {
  if (impl_) impl_->have_previous = false;
}

void ArapDeformer::setup(const Layout& layout) {
  const auto t0 = std::chrono::steady_clock::now();
  auto m = std::make_unique<Impl>();
  const int n = mesh_.num_vertices();
  m->s = detail::make_stencil(mesh_.V, mesh_.F, LaplacianWeights::Cotangent);
  m->free = layout.free;
  m->local.assign(static_cast<size_t>(n), -1);
  for (size_t k = 0; k < m->free.size(); ++k) m->local[m->free[k]] = static_cast<int>(k);
  std::vector<char> need(static_cast<size_t>(n), 0);
  for (int i : m->free) {
    need[i] = 1;
    for (int k = m->s.offsets[i]; k < m->s.offsets[i + 1]; ++k) need[m->s.nbr[k]] = 1;
  }
  for (int i = 0; i < n; ++i)
    if (need[i]) m->fitted.push_back(i);

  std::vector<Eigen::Triplet<double, int>> t;
  t.reserve(m->s.nbr.size() + m->free.size());
  for (int i : m->free) {
    double diag = 0;
    for (int k = m->s.offsets[i]; k < m->s.offsets[i + 1]; ++k) {
      diag += m->s.w[k];
      const int j = m->local[m->s.nbr[k]];
      if (j >= 0) t.emplace_back(m->local[i], j, -m->s.w[k]);
    }
    t.emplace_back(m->local[i], m->local[i], diag);
  }
  const int nf = static_cast<int>(m->free.size());
  solver::SparseMatrix L(nf, nf);
  L.setFromTriplets(t.begin(), t.end());
  try {
    m->chol.compute(L);
  } catch (const NotPositiveDefinite& e) {
    throw NotPositiveDefinite(std::string("mesh_deform::ArapDeformer::precompute(): the cotangent Laplacian of the "
                                          "free vertices is not positive definite (is some part of the ROI not "
                                          "connected to a handle or the fixed region?): ") + e.what(),
                              e.column() >= 0 ? m->free[static_cast<size_t>(e.column())] : -1);
  }
  m->R.assign(static_cast<size_t>(n), Eigen::Matrix3d::Identity());
  m->q.assign(static_cast<size_t>(n), Eigen::Quaterniond::Identity());
  m->we.resize(m->s.nbr.size());
  m->rest_sq.assign(static_cast<size_t>(n), 0.0);
  for (int i = 0; i < n; ++i)
    for (int k = m->s.offsets[i]; k < m->s.offsets[i + 1]; ++k) {
      const Eigen::Vector3d e = (mesh_.V.row(i) - mesh_.V.row(m->s.nbr[k])).transpose();
      m->we[k] = m->s.w[k] * e;
      m->rest_sq[i] += m->s.w[k] * e.squaredNorm();
    }
  impl_ = std::move(m);
  stats_ = {};
  stats_.setup_ms = ms_since(t0);
}

void ArapDeformer::solve(const HandleTransforms&, const Vertices& targets, Vertices& out) {
  const auto t_frame = std::chrono::steady_clock::now();
  Impl& m = *impl_;
  const detail::Stencil& s = m.s;
  const Vertices& V = mesh_.V;
  // Start: the previous result with this frame's handle targets, or the rest mesh.
  out = targets;
  if (options_.warm_start && m.have_previous)
    for (int i : m.free) out.row(i) = m.previous.row(i);

  const int nf = static_cast<int>(m.free.size());
  const int nr = static_cast<int>(m.fitted.size());
  // The part of the right-hand side fixed for the whole frame: − (L V)_i = − Σ_j w_ij e_ij and
  // the constrained neighbours' displacements Σ_j w_ij d_j.
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> lap(nf, 3), frame_rhs(nf, 3);
#pragma omp parallel for schedule(static)
  for (int k = 0; k < nf; ++k) {
    const int i = m.free[k];
    Eigen::Vector3d l = Eigen::Vector3d::Zero(), c = Eigen::Vector3d::Zero();
    for (int e = s.offsets[i]; e < s.offsets[i + 1]; ++e) {
      l += m.we[e];
      const int j = s.nbr[e];
      if (m.local[j] < 0) c += s.w[e] * (targets.row(j) - V.row(j)).transpose();
    }
    lap.row(k) = l.transpose();
    frame_rhs.row(k) = (c - l).transpose();
  }
  solver::DenseMatrix b(nf, 3);
  double rot_ms = 0, solve_ms = 0, last_energy = -1;
  int it = 0, fallbacks = 0;
  for (; it < options_.max_iterations;) {
    auto t0 = std::chrono::steady_clock::now();
    // Local step: R_i maximizes tr(R_iᵀ Σ_j w_ij ẽ_ij e_ijᵀ) (Sorkine & Alexa Eq. 5–6).
    double energy = 0;
#pragma omp parallel for schedule(static) reduction(+ : energy, fallbacks)
    for (int r = 0; r < nr; ++r) {
      const int i = m.fitted[r];
      Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
      double sq = m.rest_sq[i];
      const Eigen::Vector3d qi = out.row(i).transpose();
      for (int k = s.offsets[i]; k < s.offsets[i + 1]; ++k) {
        const Eigen::Vector3d et = qi - out.row(s.nbr[k]).transpose();
        A.noalias() += et * m.we[k].transpose();
        sq += s.w[k] * et.squaredNorm();
      }
      bool fell_back = false;
      m.R[i] = detail::nearest_rotation(A, m.q[i], &fell_back);
      fallbacks += fell_back;
      energy += sq - 2 * (m.R[i].transpose() * A).trace();
    }
    // Right-hand side (Eq. 8): b_i = Σ_j w_ij/2 (R_i + R_j)(v_i − v_j)
    //                              = R_i (L V)_i / 2 + Σ_j R_j w_ij e_ij / 2, plus the frame part.
#pragma omp parallel for schedule(static)
    for (int k = 0; k < nf; ++k) {
      const int i = m.free[k];
      Eigen::Vector3d acc = m.R[i] * lap.row(k).transpose();
      for (int l = s.offsets[i]; l < s.offsets[i + 1]; ++l) acc.noalias() += m.R[s.nbr[l]] * m.we[l];
      b.row(k) = 0.5 * acc.transpose() + frame_rhs.row(k);
    }
    rot_ms += ms_since(t0);
    ++it;
    t0 = std::chrono::steady_clock::now();
    const solver::DenseMatrix d = m.chol.solve(b);
    for (int k = 0; k < nf; ++k) out.row(m.free[k]) = V.row(m.free[k]) + d.row(k);
    solve_ms += ms_since(t0);
    const bool converged = options_.tolerance > 0 && last_energy >= 0 &&
                           last_energy - energy <= options_.tolerance * std::max(last_energy, 1e-300);
    last_energy = energy;
    stats_.energy = energy;
    if (converged) break;
  }
  m.previous = out;
  m.have_previous = true;
  stats_.iterations = it;
  stats_.rotation_fallbacks = fallbacks;
  stats_.rotations_ms = rot_ms;
  stats_.solves_ms = solve_ms;
  stats_.frame_ms = ms_since(t_frame);
}

}  // namespace lapis::mesh_deform
