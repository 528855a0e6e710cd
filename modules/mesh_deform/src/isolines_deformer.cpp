#include "lapis/mesh_deform/isolines_deformer.h"

#include <chrono>
#include <cmath>

#include <Eigen/Cholesky>

#include "anderson.h"
#include "isoline_basis.h"
#include "isoline_guides.h"
#include "isoline_samples.h"
#include "isoline_system.h"
#include "lapis/geometry/laplacian.h"
#include "rotation_fit.h"
#include "stencil.h"

namespace lapis::mesh_deform {
namespace {

using solver::DenseMatrix;

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

[[noreturn]] void fail_option(const std::string& what) {
  throw InvalidArgument("mesh_deform::IsolinesDeformer::set_options(): " + what);
}

void check_options(const IsolinesOptions& o) {
  auto positive = [](double x) { return std::isfinite(x) && x > 0; };
  if (o.isolines < 2) fail_option("isolines = " + std::to_string(o.isolines) + ", expected >= 2 (§4.1: s = 0 and 1)");
  if (!positive(o.omega)) fail_option("omega must be finite and > 0");
  if (!std::isfinite(o.beta) || o.beta < 0) fail_option("beta must be finite and >= 0");
  if (o.anderson_depth < 0) fail_option("anderson_depth must be >= 0");
  if (!std::isfinite(o.guide_angle) || o.guide_angle < 0 || !std::isfinite(o.guide_weight) || o.guide_weight < 0)
    fail_option("guide_angle and guide_weight must be finite and >= 0");
  if (o.max_iterations < 1) fail_option("max_iterations = " + std::to_string(o.max_iterations) + ", expected >= 1");
  if (!std::isfinite(o.tolerance) || o.tolerance < 0) fail_option("tolerance must be finite and >= 0");
  if (o.triangle_budget < 0 || o.min_triangles_per_isoline < 0)
    fail_option("triangle_budget and min_triangles_per_isoline must be >= 0");
  if (!std::isfinite(o.fields.point_handle_radius) || o.fields.point_handle_radius < 0)
    fail_option("fields.point_handle_radius must be finite and >= 0");
}

detail::NormalFit normal_fit(IsolineFit f) {
  switch (f) {
    case IsolineFit::Similarity:
      return detail::NormalFit::Similarity;
    case IsolineFit::Paper:
      return detail::NormalFit::Paper;
    case IsolineFit::Rotation:
      break;
  }
  return detail::NormalFit::Rotation;
}

// R = I: every isoline's r = [I 0], block ℓ of R is rᵀ = [I; 0].
DenseMatrix identity_transforms(int m) {
  DenseMatrix R = DenseMatrix::Zero(4 * m, 3);
  for (int l = 0; l < m; ++l) R.block<3, 3>(4 * l, 0).setIdentity();
  return R;
}

}  // namespace

struct IsolinesDeformer::Impl {
  HandleSets sets;
  HandleFields fields;
  detail::IsolineBasis basis;
  detail::IsolineSamples samples;
  Eigen::SparseMatrix<double> L;  // Eq. 6 mode only
  detail::Stencil stencil;        // Eq. 6 mode: the per-vertex rotations of δ(X)
  Vertices delta;                 // normalized rest Laplacian coordinates δ̄
  std::vector<detail::HandleGroup> groups;
  std::vector<DenseMatrix> G;  // ω² W_xᵀΦᵀQ per group
  DenseMatrix P;               // W_xᵀLᵀW_δ
  DenseMatrix UtU_model;       // Eq. 6/10's normal matrix, without the ridge
  DenseMatrix UtU;             // the same with this frame's guide rows
  Eigen::LLT<DenseMatrix> chol;
  DenseMatrix rest_residual;  // the rounding of Eq. 6/10 at rest, taken out of every step
  double ridge = 0;
  double guide_unit = 0;  // mean diagonal of the Laplacian part
  detail::IsolineGuides guides;
  DenseMatrix R;                       // current transforms, 4m by 3
  std::vector<Eigen::Quaterniond> q;   // per isoline: last fitted rotation
  std::vector<Eigen::Quaterniond> vq;  // Eq. 6 mode, per vertex
  std::vector<int> free;
  Vertices last;  // the last full frame, for previews
  bool have_last = false;

  DenseMatrix handle_term(const HandleTransforms& t, int num_regions) const;
  DenseMatrix reduced_data(const DenseMatrix& R, detail::NormalFit fit);
  DenseMatrix full_data(const DenseMatrix& R);
  DenseMatrix step(const DenseMatrix& rhs) const;
  DenseMatrix residual_at_rest(const HandleTransforms& identity, int num_regions, IsolineSolve solve,
                               detail::NormalFit fit);
  void factorize();
  DenseMatrix guide_term(double weight) const;
};

// UᵀU (+ guide rows) + λI.
void IsolinesDeformer::Impl::factorize() {
  DenseMatrix A = UtU;
  A.diagonal().array() += ridge;
  chol.compute(A);
  if (chol.info() != Eigen::Success)
    throw NotPositiveDefinite("mesh_deform::IsolinesDeformer::precompute(): the reduced normal matrix UᵀU (" +
                                  std::to_string(A.rows()) + " unknowns) is not positive definite",
                              -1);
}

// w Σ_ℓ guided [G_ℓᵀ; 0], the right-hand side of the guide rows w ‖A_ℓ − G_ℓ‖²_F.
DenseMatrix IsolinesDeformer::Impl::guide_term(double weight) const {
  DenseMatrix g = DenseMatrix::Zero(UtU.rows(), 3);
  for (size_t l = 0; l < guides.guided.size(); ++l)
    if (guides.guided[l]) g.middleRows<3>(4 * static_cast<Eigen::Index>(l)) = weight * guides.target[l].transpose();
  return g;
}

// The change of R that solves (UᵀU + λI) R' = rhs + λR, from the residual and with one step of
// refinement: ω² makes UᵀU ill-conditioned (~1e10), and a fixed point (the identity, a rigid
// motion) then comes out exact instead of perturbed by the rounding of the full solve.
DenseMatrix IsolinesDeformer::Impl::step(const DenseMatrix& rhs) const {
  const DenseMatrix residual = rhs - rest_residual - UtU * R;
  DenseMatrix d = chol.solve(residual);
  d += chol.solve(residual - UtU * d - ridge * d);
  return d;
}

// The residual of Eq. 6/10 at the rest transforms with identity handles. It is zero but for the
// rounding of the assembly (~1e-16 of UᵀU), which ω²'s conditioning (~1e10) would turn into a
// drift of the identity by 1e-9 of the diagonal that depends on the thread count; taking it out
// of every step makes the rest pose an exact fixed point. Larger, it would be a model error.
DenseMatrix IsolinesDeformer::Impl::residual_at_rest(const HandleTransforms& identity, int num_regions,
                                                     IsolineSolve solve, detail::NormalFit fit) {
  const DenseMatrix data = solve == IsolineSolve::Reduced ? reduced_data(R, fit) : full_data(R);
  const DenseMatrix rest = UtU_model * R;
  DenseMatrix r = data + handle_term(identity, num_regions) - rest;
  if (r.norm() > 1e-10 * rest.norm())
    throw SolverFailure(
        "mesh_deform::IsolinesDeformer::precompute(): the rest pose is not a fixed point of the "
        "reduced model (relative residual " +
        std::to_string(r.norm() / rest.norm()) + ")");
  return r;
}

// Σ_g ω² G_g C_g: a region handle's C is its transform in normalized coordinates, transposed.
DenseMatrix IsolinesDeformer::Impl::handle_term(const HandleTransforms& t, int num_regions) const {
  DenseMatrix out = DenseMatrix::Zero(P.rows(), 3);
  const Eigen::Vector3d c = basis.center;
  const double d = basis.scale;
  for (size_t g = 0; g < groups.size(); ++g) {
    const int h = static_cast<int>(g) - (sets.has_fixed_region ? 1 : 0);
    if (groups[g].affine) {
      Eigen::Matrix<double, 4, 3> C = Eigen::Matrix<double, 4, 3>::Zero();
      C.topRows<3>().setIdentity();
      if (h >= 0) {
        const Eigen::Matrix3d A = t.regions[h].topLeftCorner<3, 3>();
        const Eigen::Vector3d b = t.regions[h].topRightCorner<3, 1>();
        C.topRows<3>() = A.transpose();
        C.row(3) = ((A * c + b - c) / d).transpose();
      }
      out.noalias() += G[g] * C;
    } else {
      const int v = groups[g].vertices[0];
      const Eigen::RowVector3d x = basis.rest.row(v) + t.points[h - num_regions].transpose() / d;
      out.noalias() += G[g] * x;
    }
  }
  return out;
}

// Eq. 10's P R_δ: the isolines' fits from the sampled triangles only.
DenseMatrix IsolinesDeformer::Impl::reduced_data(const DenseMatrix& Rx, detail::NormalFit fit) {
  const Vertices X = detail::sample_positions(samples, basis.sets, detail::transform_blocks(Rx));
  std::vector<Eigen::Matrix3d> r;
  detail::fit_isolines(samples, X, fit, q, r);
  DenseMatrix Rd(3 * r.size(), 3);
  for (size_t l = 0; l < r.size(); ++l) Rd.middleRows<3>(3 * l) = r[l].transpose();
  return P * Rd;
}

// Eq. 6's W_xᵀLᵀδ(W_x R): δ_k(X) = R_k δ̄_k with R_k the rotation of vertex k's 1-ring (the
// local step of ARAP), which makes δ(X̄) = δ̄ and δ of a rigid motion that motion.
DenseMatrix IsolinesDeformer::Impl::full_data(const DenseMatrix& Rx) {
  const int n = basis.vertices;
  Vertices X(n, 3), D(n, 3);
  const detail::TransformBlocks B = detail::transform_blocks(Rx);
  detail::for_vertices(n, [&](std::ptrdiff_t k) { X.row(k) = basis.position(static_cast<int>(k), B).transpose(); });
  detail::for_vertices(n, [&](std::ptrdiff_t k) {
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
    for (int e = stencil.offsets[k]; e < stencil.offsets[k + 1]; ++e) {
      const int j = stencil.nbr[e];
      A += stencil.w[e] * (X.row(j) - X.row(k)).transpose() * (basis.rest.row(j) - basis.rest.row(k));
    }
    D.row(k) = (detail::nearest_rotation(A, vq[k]) * delta.row(k).transpose()).transpose();
  });
  const Vertices Y = L * D;
  return detail::basis_transpose_times(basis, Y);
}

IsolinesDeformer::IsolinesDeformer(TriMesh mesh, IsolinesOptions options)
    : Deformer(std::move(mesh)), options_(options) {
  check_options(options_);
}

IsolinesDeformer::~IsolinesDeformer() = default;

void IsolinesDeformer::set_options(const IsolinesOptions& o) {
  check_options(o);
  const bool same_model = o.isolines == options_.isolines && o.solve == options_.solve && o.omega == options_.omega &&
                          o.beta == options_.beta && o.triangle_budget == options_.triangle_budget &&
                          o.min_triangles_per_isoline == options_.min_triangles_per_isoline &&
                          o.fields.point_handle_radius == options_.fields.point_handle_radius;
  options_ = o;
  if (!same_model) mark_dirty();
}

void IsolinesDeformer::reset_warm_start() {
  if (!impl_) return;
  impl_->R = identity_transforms(impl_->basis.count());
  impl_->guides.reset(static_cast<int>(impl_->guides.angle.size()), impl_->basis.count());
  impl_->UtU = impl_->UtU_model;
  impl_->factorize();
}

namespace {

// The Φ rows of Eq. 2: the fixed region (held by the identity), each region handle, and each
// point handle's own vertex (its disc only shapes the field).
std::vector<detail::HandleGroup> handle_groups(const Layout& layout, const Selection& s) {
  std::vector<detail::HandleGroup> groups;
  detail::HandleGroup fixed;
  for (int v : layout.constrained)
    if (layout.role[v] == VertexRole::Fixed) fixed.vertices.push_back(v);
  if (!fixed.vertices.empty()) groups.push_back(std::move(fixed));
  for (const auto& h : s.region_handles) groups.push_back({h, true});
  for (int v : s.point_handles) groups.push_back({{v}, false});
  return groups;
}

}  // namespace

void IsolinesDeformer::setup(const Layout& layout) {
  const auto t_setup = std::chrono::steady_clock::now();
  impl_.reset();
  auto m = std::make_unique<Impl>();
  report_ = {};
  m->sets = handle_sets(mesh_, layout, selection(), options_.fields);
  m->fields = harmonic_fields(mesh_, m->sets);
  m->basis = detail::make_isoline_basis(mesh_.V, m->fields.phi, options_.isolines);
  const int iso = m->basis.count();

  auto t0 = std::chrono::steady_clock::now();
  const int budget = options_.triangle_budget > 0 ? options_.triangle_budget : 30 * iso;
  m->samples = detail::sample_isolines(m->basis, mesh_.F, m->fields.phi, budget, options_.min_triangles_per_isoline);
  report_.extraction_ms = ms_since(t0);

  t0 = std::chrono::steady_clock::now();
  Eigen::SparseMatrix<double> L = geometry::cotan_laplacian(mesh_);  // cotangents do not see the normalization
  m->delta = L * m->basis.rest;
  m->groups = handle_groups(layout, selection());
  detail::IsolineSystem sys = detail::assemble_isoline_system(m->basis, L, m->delta, m->groups);
  // ω and β weigh rows of different counts and units (n Laplacian rows, |Φ| handle rows, m − K
  // smoothness rows): relative to the Laplacian part, they mean the same at every resolution.
  const double lap = sys.laplacian.trace();
  const double w2 = options_.omega * options_.omega * (lap > 0 ? lap / sys.handles.trace() : 1.0);
  const double b2 = options_.beta * options_.beta * (lap > 0 ? lap / sys.smoothness.trace() : 1.0);
  m->UtU_model = sys.laplacian + w2 * sys.handles + b2 * sys.smoothness;
  m->UtU = m->UtU_model;
  // The ridge for rank-deficient cases (coplanar influence, point handles only) is relative to
  // the Laplacian part: ω²'s share of the trace would make it slow the iteration down.
  m->guide_unit = (lap > 0 ? lap : m->UtU.trace()) / m->UtU.rows();
  m->ridge = 1e-10 * m->guide_unit;
  m->factorize();
  m->guides.reset(layout.num_region_handles, iso);
  for (DenseMatrix& g : sys.G) m->G.push_back(w2 * g);
  m->P = std::move(sys.P);
  if (options_.solve == IsolineSolve::Full) {
    m->stencil =
        detail::make_stencil(m->basis.rest, mesh_.F, LaplacianWeights::Cotangent, detail::ObtuseAngles::ClampToZero);
    m->L = std::move(L);
    m->vq.assign(static_cast<size_t>(mesh_.num_vertices()), Eigen::Quaterniond::Identity());
  }
  report_.assembly_ms = ms_since(t0);

  m->R = identity_transforms(iso);
  m->q.assign(static_cast<size_t>(iso), Eigen::Quaterniond::Identity());
  m->rest_residual = m->residual_at_rest(HandleTransforms::identity(selection()), layout.num_region_handles,
                                         options_.solve, normal_fit(options_.fit));
  m->free = layout.free;
  report_.handles = m->sets.size();
  report_.sets = m->basis.sets;
  report_.unknowns = 4 * iso;
  report_.crossed_triangles = m->samples.crossed;
  report_.sampled_triangles = m->samples.size();
  report_.iteration_vertices = static_cast<int>(m->samples.vertices.size());
  report_.iteration_rows = options_.solve == IsolineSolve::Full ? mesh_.num_vertices() : report_.iteration_vertices;
  report_.field_overshoot = m->fields.overshoot;
  report_.field_residual = m->fields.residual;
  report_.field_factor_nnz = m->fields.factor_nnz;
  report_.fields_factorize_ms = m->fields.factorize_ms;
  report_.fields_solve_ms = m->fields.solve_ms;
  impl_ = std::move(m);
  report_.setup_ms = ms_since(t_setup);
}

void IsolinesDeformer::solve(const HandleTransforms& transforms, const Vertices& /*targets*/, Vertices& out) {
  const auto t_frame = std::chrono::steady_clock::now();
  Impl& m = *impl_;
  DenseMatrix gc = m.handle_term(transforms, layout().num_region_handles);
  if (options_.large_rotations) {
    const double w = options_.guide_weight * m.guide_unit;
    if (m.guides.update(transforms, m.basis, m.sets, options_.guide_angle)) {
      m.UtU = m.UtU_model;
      for (size_t l = 0; l < m.guides.guided.size(); ++l)
        if (m.guides.guided[l]) m.UtU.diagonal().segment<3>(4 * static_cast<Eigen::Index>(l)).array() += w;
      m.factorize();
    }
    gc += m.guide_term(w);
  }
  const detail::NormalFit fit = normal_fit(options_.fit);
  report_.steps.clear();
  report_.iteration_ms.clear();
  auto t0 = std::chrono::steady_clock::now();
  // Eq. 10 / Eq. 6 from the last frame's transforms (§3: X⁰ the current positions). The ridge
  // pulls toward them, so it vanishes at convergence.
  // The step size is the plain iteration's, ‖g(R) − R‖ / ‖R‖, also when accelerated.
  detail::Anderson accel(options_.anderson_depth);
  for (int it = 0; it < options_.max_iterations; ++it) {
    const auto t_it = std::chrono::steady_clock::now();
    const DenseMatrix data = options_.solve == IsolineSolve::Reduced ? m.reduced_data(m.R, fit) : m.full_data(m.R);
    const DenseMatrix d = m.step(data + gc);
    const double step = d.norm() / std::max(m.R.norm(), 1e-300);
    report_.steps.push_back(step);
    const Eigen::Map<const Eigen::VectorXd> x(m.R.data(), m.R.size());
    const Eigen::VectorXd g = x + Eigen::Map<const Eigen::VectorXd>(d.data(), d.size());
    const Eigen::VectorXd next = step < options_.tolerance ? g : accel.next(x, g);
    m.R = Eigen::Map<const DenseMatrix>(next.data(), m.R.rows(), m.R.cols());
    report_.iteration_ms.push_back(ms_since(t_it));
    if (step < options_.tolerance) break;
  }
  report_.iterations = static_cast<int>(report_.steps.size());
  report_.iterate_ms = ms_since(t0);

  t0 = std::chrono::steady_clock::now();
  const int stride = m.have_last ? preview_stride_ : 0;
  const detail::TransformBlocks B = detail::transform_blocks(m.R);
  detail::for_vertices(m.free.size(), [&](std::ptrdiff_t k) {
    const int v = m.free[k];
    if (stride > 1 && k % stride != 0)
      out.row(v) = m.last.row(v);
    else
      out.row(v) = m.basis.denormalized(m.basis.position(v, B)).transpose();
  });
  // Only a preview needs the last frame (a #V × 3 copy: 27 MB at 1.1M vertices).
  m.have_last = preview_stride_ > 1;
  if (m.have_last) m.last = out;
  report_.reconstruct_ms = ms_since(t0);
  report_.frame_ms = ms_since(t_frame);
}

namespace {
[[noreturn]] void not_set_up(const char* fn) {
  throw InvalidArgument(std::string("mesh_deform::IsolinesDeformer::") + fn + ": no model yet, call precompute()");
}
}  // namespace

const Eigen::MatrixXd& IsolinesDeformer::fields() const {
  if (!impl_) not_set_up("fields()");
  return impl_->fields.phi;
}

Eigen::VectorXd IsolinesDeformer::rigidity() const { return handle_rigidity(mesh_, fields()); }

int IsolinesDeformer::isoline_sets() const {
  if (!impl_) not_set_up("isoline_sets()");
  return impl_->basis.sets;
}

std::vector<IsolineSegment> IsolinesDeformer::isolines_of_set(int set) const {
  if (set < 0 || set >= isoline_sets())
    throw InvalidArgument("mesh_deform::IsolinesDeformer::isolines_of_set(): set " + std::to_string(set) +
                          " out of range [0, " + std::to_string(isoline_sets()) + ")");
  return detail::isoline_set_segments(impl_->basis, mesh_.F, impl_->fields.phi, set);
}

const Eigen::MatrixXd& IsolinesDeformer::isoline_transforms() const {
  if (!impl_) not_set_up("isoline_transforms()");
  return impl_->R;
}

Vertices IsolinesDeformer::reconstruct(const std::vector<int>& vertices) const {
  if (!impl_) not_set_up("reconstruct()");
  Vertices X(vertices.size(), 3);
  const detail::TransformBlocks B = detail::transform_blocks(impl_->R);
  for (size_t k = 0; k < vertices.size(); ++k) {
    const int v = vertices[k];
    if (v < 0 || v >= mesh_.num_vertices())
      throw InvalidArgument("mesh_deform::IsolinesDeformer::reconstruct(): vertex " + std::to_string(v) +
                            " out of range");
    X.row(k) = impl_->basis.denormalized(impl_->basis.position(v, B)).transpose();
  }
  return X;
}

const char* to_string(IsolineSolve s) { return s == IsolineSolve::Full ? "full" : "reduced"; }

const char* to_string(IsolineFit f) {
  switch (f) {
    case IsolineFit::Similarity:
      return "similarity";
    case IsolineFit::Paper:
      return "paper";
    case IsolineFit::Rotation:
      break;
  }
  return "rotation";
}

IsolineSolve isoline_solve_from_name(const std::string& name) {
  for (IsolineSolve s : {IsolineSolve::Reduced, IsolineSolve::Full})
    if (name == to_string(s)) return s;
  throw InvalidArgument("mesh_deform::isoline_solve_from_name(): unknown mode '" + name +
                        "', expected reduced or full");
}

IsolineFit isoline_fit_from_name(const std::string& name) {
  for (IsolineFit f : {IsolineFit::Rotation, IsolineFit::Similarity, IsolineFit::Paper})
    if (name == to_string(f)) return f;
  throw InvalidArgument("mesh_deform::isoline_fit_from_name(): unknown fit '" + name +
                        "', expected rotation, similarity or paper");
}

}  // namespace lapis::mesh_deform
