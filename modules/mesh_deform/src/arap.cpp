#include "lapis/mesh_deform/arap.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "handle_rotation_blend.h"
#include "lapis/core/parallel_for.h"
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
// Everything per vertex is stored in spatial order (detail::spatial_order): the local step's
// loops gather neighbours' positions and rotations, and in the mesh's own order (a
// Loop-subdivided one's above all) those gathers miss the cache and cost as much as the fits.
struct ArapDeformer::Impl {
  std::vector<int> order;   // internal index -> mesh vertex
  Vertices rest;            // rest positions, internal order
  detail::Stencil s;        // cotangent weights, neighbour lists in contiguous arrays
  std::vector<int> free;    // ascending internal indices
  std::vector<int> local;   // vertex -> index among free, -1 for constrained
  std::vector<int> fitted;  // vertices whose rotation a free vertex's row reads
  solver::Cholesky chol;
  std::vector<Eigen::Vector3d> we;    // per stencil entry: w_ij (v_i − v_j), contiguous
  std::vector<double> rest_sq;        // per vertex: Σ_j w_ij ‖v_i − v_j‖²
  std::vector<Eigen::Matrix3d> R;     // #V rotations
  std::vector<Eigen::Quaterniond> q;  // the same rotations, each fit's start in the next iteration
  Vertices X, targets;                // this frame's iterate and handle targets, internal order
  bool have_previous = false;         // R holds the rotations of the last frame's result
  // Per frame, over the free vertices: (L V)_i = Σ_j w_ij e_ij, and the right-hand side's part
  // that stays fixed over the frame, Σ_j w_ij d_j over constrained j minus (L V)_i.
  Vertices lap, frame_rhs;
  solver::DenseMatrix b;
  // #V by #region handles, internal order: the harmonic field of each region handle (1 on it,
  // 0 on the fixed region and the other handles), which spreads the handles' rotations over
  // the ROI for a frame that starts cold.
  solver::DenseMatrix handle_fields;

  void start_frame(const Vertices& mesh_targets);
  void build_handle_fields(const Layout& layout);
  void blend_handle_rotations(const HandleTransforms& transforms);
  void identity_rotations();
  double fit_rotations(int& fallbacks);
  void assemble_rhs();
  void global_step();
};

// L_ff φ_f = −L_fc φ_c per region handle, with the factor the global step already has.
void ArapDeformer::Impl::build_handle_fields(const Layout& layout) {
  const int n = static_cast<int>(order.size()), nf = static_cast<int>(free.size());
  const int nh = layout.num_region_handles;
  handle_fields = solver::DenseMatrix::Zero(n, nh);
  if (nh == 0) return;
  auto handle_at = [&](int i) {  // region handle of internal vertex i, or -1
    const int v = order[i];
    return layout.role[v] == VertexRole::RegionHandle ? layout.handle_of[v] : -1;
  };
  solver::DenseMatrix rhs = solver::DenseMatrix::Zero(nf, nh);
  for (int k = 0; k < nf; ++k)
    for (int e = s.offsets[free[k]]; e < s.offsets[free[k] + 1]; ++e)
      if (const int h = local[s.nbr[e]] < 0 ? handle_at(s.nbr[e]) : -1; h >= 0) rhs(k, h) += s.w[e];
  const solver::DenseMatrix phi = chol.solve(rhs);
  for (int k = 0; k < nf; ++k) handle_fields.row(free[k]) = phi.row(k);
  for (int i = 0; i < n; ++i)
    if (const int h = local[i] < 0 ? handle_at(i) : -1; h >= 0) handle_fields(i, h) = 1;
}

// A cold frame's first rotations: each vertex turns by the field-weighted blend of the region
// handles' rotation vectors (the fixed region and point handles count as the identity). A
// rigid motion shared by every handle then holds everywhere and the first global step
// reproduces it exactly.
void ArapDeformer::Impl::blend_handle_rotations(const HandleTransforms& transforms) {
  const std::vector<Eigen::Vector3d> r = detail::region_rotation_vectors(transforms);
  detail::for_vertices(fitted.size(), [&](std::ptrdiff_t k) {
    const int i = fitted[static_cast<size_t>(k)];
    q[i] = detail::blended_rotation(handle_fields.row(i), r);
    R[i] = q[i].toRotationMatrix();
  });
}

void ArapDeformer::Impl::identity_rotations() {
  std::fill(R.begin(), R.end(), Eigen::Matrix3d::Identity());
  std::fill(q.begin(), q.end(), Eigen::Quaterniond::Identity());
}

void ArapDeformer::Impl::global_step() {
  const solver::DenseMatrix d = chol.solve(b);
  for (size_t k = 0; k < free.size(); ++k) X.row(free[k]) = rest.row(free[k]) + d.row(static_cast<Eigen::Index>(k));
}

// Targets into internal order, placed at the constrained vertices of the iterate (the global
// steps place the free ones).
void ArapDeformer::Impl::start_frame(const Vertices& mesh_targets) {
  const int n = static_cast<int>(order.size()), nf = static_cast<int>(free.size());
  targets.resize(n, 3);
  for (int k = 0; k < n; ++k) targets.row(k) = mesh_targets.row(order[k]);
  if (X.rows() != n) X = targets;
  for (int i = 0; i < n; ++i)
    if (local[i] < 0) X.row(i) = targets.row(i);
  lap.resize(nf, 3);
  frame_rhs.resize(nf, 3);
  b.resize(nf, 3);
  detail::for_vertices(free.size(), [&](std::ptrdiff_t k) {
    const int i = free[static_cast<size_t>(k)];
    Eigen::RowVector3d l = Eigen::RowVector3d::Zero(), c = Eigen::RowVector3d::Zero();
    for (int e = s.offsets[i]; e < s.offsets[i + 1]; ++e) {
      l += we[e].transpose();
      const int j = s.nbr[e];
      if (local[j] < 0) c += s.w[e] * (targets.row(j) - rest.row(j));
    }
    lap.row(k) = l;
    frame_rhs.row(k) = c - l;
  });
}

// Local step (Sorkine & Alexa Eq. 5–6): R_i maximizes tr(R_iᵀ A_i), A_i = Σ_j w_ij ẽ_ij e_ijᵀ,
// each fit started from the vertex's last rotation. Returns the ARAP energy of the iterate
// under the new rotations, Σ_j w_ij ‖ẽ_ij − R_i e_ij‖² = Σ_j w_ij (‖ẽ_ij‖² + ‖e_ij‖²) − 2 tr(R_iᵀ A_i).
double ArapDeformer::Impl::fit_rotations(int& fallbacks) {
  struct Sums {
    double energy = 0;
    int fell = 0;
    Sums& operator+=(const Sums& o) {
      energy += o.energy;
      fell += o.fell;
      return *this;
    }
  };
  auto fit_range = [&](std::ptrdiff_t lo, std::ptrdiff_t hi) {
    Sums part;
    for (std::ptrdiff_t r = lo; r < hi; ++r) {
      const int i = fitted[static_cast<size_t>(r)];
      Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
      double sq = rest_sq[i];
      const Eigen::Vector3d xi = X.row(i).transpose();
      for (int k = s.offsets[i]; k < s.offsets[i + 1]; ++k) {
        const Eigen::Vector3d et = xi - X.row(s.nbr[k]).transpose();
        A.noalias() += et * we[k].transpose();
        sq += s.w[k] * et.squaredNorm();
      }
      bool fell_back = false;
      R[i] = detail::nearest_rotation(A, q[i], &fell_back);
      part.fell += fell_back;
      part.energy += sq - 2 * (R[i].transpose() * A).trace();
    }
    return part;
  };
  const Sums sums =
      core::parallel_sum<Sums>(0, static_cast<std::ptrdiff_t>(fitted.size()), detail::kVertexChunk, fit_range);
  fallbacks += sums.fell;
  return sums.energy;
}

// Right-hand side (Eq. 8): b_i = Σ_j w_ij/2 (R_i + R_j)(v_i − v_j)
//                              = R_i (L V)_i / 2 + Σ_j R_j w_ij e_ij / 2, plus the frame part.
void ArapDeformer::Impl::assemble_rhs() {
  detail::for_vertices(free.size(), [&](std::ptrdiff_t k) {
    const int i = free[static_cast<size_t>(k)];
    Eigen::Vector3d acc = R[i] * lap.row(k).transpose();
    for (int l = s.offsets[i]; l < s.offsets[i + 1]; ++l) acc.noalias() += R[s.nbr[l]] * we[l];
    b.row(k) = 0.5 * acc.transpose() + frame_rhs.row(k);
  });
}

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
  m->order = detail::spatial_order(mesh_.V);
  const std::vector<int> rank = detail::rank_in(m->order);
  m->rest.resize(n, 3);
  for (int k = 0; k < n; ++k) m->rest.row(k) = mesh_.V.row(m->order[k]);
  geometry::Faces F = mesh_.F;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c) F(f, c) = rank[F(f, c)];
  m->s = detail::make_stencil(m->rest, F, LaplacianWeights::Cotangent, detail::ObtuseAngles::ClampToZero);
  for (int v : layout.free) m->free.push_back(rank[v]);
  std::sort(m->free.begin(), m->free.end());
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
                                          "connected to a handle or the fixed region?): ") +
                                  e.what(),
                              e.column() >= 0 ? m->order[m->free[static_cast<size_t>(e.column())]] : -1);
  }
  m->R.assign(static_cast<size_t>(n), Eigen::Matrix3d::Identity());
  m->q.assign(static_cast<size_t>(n), Eigen::Quaterniond::Identity());
  m->we.resize(m->s.nbr.size());
  m->rest_sq.assign(static_cast<size_t>(n), 0.0);
  for (int i = 0; i < n; ++i)
    for (int k = m->s.offsets[i]; k < m->s.offsets[i + 1]; ++k) {
      const Eigen::Vector3d e = (m->rest.row(i) - m->rest.row(m->s.nbr[k])).transpose();
      m->we[k] = m->s.w[k] * e;
      m->rest_sq[i] += m->s.w[k] * e.squaredNorm();
    }
  m->build_handle_fields(layout);
  impl_ = std::move(m);
  report_ = {};
  report_.setup_ms = ms_since(t0);
}

// Each iteration is a global step with the current rotations, then the rotations of its
// result (CGAL's order). A warm frame starts from the rotations the last frame ended with, a
// cold one from ArapOptions::cold_start's; the frame's own targets never enter a rotation fit
// before a global step has placed the free vertices around them.
void ArapDeformer::solve(const HandleTransforms& transforms, const Vertices& targets, Vertices& out) {
  const auto t_frame = std::chrono::steady_clock::now();
  Impl& m = *impl_;
  const bool cold = !(options_.warm_start && m.have_previous);
  m.start_frame(targets);
  double rot_ms = 0, solve_ms = 0, last_energy = -1;
  int it = 0, fallbacks = 0;
  auto t0 = std::chrono::steady_clock::now();
  if (cold) {
    if (options_.cold_start == ColdStart::HandleRotations)
      m.blend_handle_rotations(transforms);
    else
      m.identity_rotations();
  }
  rot_ms += ms_since(t0);
  while (it < options_.max_iterations) {
    t0 = std::chrono::steady_clock::now();
    m.assemble_rhs();
    rot_ms += ms_since(t0);
    t0 = std::chrono::steady_clock::now();
    m.global_step();
    solve_ms += ms_since(t0);
    ++it;
    t0 = std::chrono::steady_clock::now();
    const double energy = m.fit_rotations(fallbacks);
    rot_ms += ms_since(t0);
    const bool converged = options_.tolerance > 0 && last_energy >= 0 &&
                           last_energy - energy <= options_.tolerance * std::max(last_energy, 1e-300);
    last_energy = energy;
    report_.energy = energy;
    if (converged) break;
  }
  out.resize(m.X.rows(), 3);
  for (size_t k = 0; k < m.order.size(); ++k) out.row(m.order[k]) = m.X.row(static_cast<Eigen::Index>(k));
  m.have_previous = true;
  report_.iterations = it;
  report_.rotation_fallbacks = fallbacks;
  report_.rotations_ms = rot_ms;
  report_.solves_ms = solve_ms;
  report_.frame_ms = ms_since(t_frame);
}

}  // namespace lapis::mesh_deform
