#include "lapis/mesh_deform/implicit_laplacian.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "handle_rotation_blend.h"
#include "implicit_first_system.h"
#include "implicit_rest.h"
#include "lapis/geometry/polar.h"
#include "lapis/solver/least_squares.h"
#include "lapis/solver/side_by_side.h"
#include "rotation_fit.h"
#include "rotation_guide.h"
#include "sparse_rows.h"
#include "stencil.h"

namespace lapis::mesh_deform {

using detail::SparseRows;

namespace {

// Guide bands between the fixed region and a guided handle: 8 bands split the accumulated
// angle into 9 steps, so up to 9π stays below π per step.
constexpr int kGuideLevels = 8;

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// Eq. 2.8's right-hand sides (one per block, empty for zero) and fixed displacements.
struct FirstSystemInput {
  std::vector<solver::DenseMatrix> rhs;
  solver::DenseMatrix fixed;
  int transform_block = -1;  // index in rhs of the transformation constraints, if any
};

}  // namespace

// Both systems are solved for the displacement from the rest state rather than for the
// positions: identity handle transforms then give an exactly zero right-hand side, so the
// rest mesh comes back to rounding level however ill-conditioned the normal matrix is.
struct ImplicitLaplacianDeformer::Impl {
  detail::WorkMesh w;
  detail::GradientStencils G;
  std::vector<int> free, constrained;
  std::vector<int> transform_vertex;  // rows of the transformation-constraint block (3 each)
  std::vector<int> transform_handle;  // region handle whose linear part is W, -1: identity
  solver::LeastSquares first{1};
  solver::LeastSquares second{1};
  bool has_coherence = false;
  // Kept for the large-rotation guide system, built on the first frame that needs it; it
  // reuses first's blocks: E_L is block 0, the others' ids are -1 when absent.
  detail::Stencil stencil;
  int block_R = -1, block_T = -1, block_B = -1;
  double weight_R = 0, weight_T = 0;
  std::vector<Eigen::Vector3d> accumulated;  // per region handle: rotation vector over the drag
  std::vector<int> guided_for;               // handles the guide system was built for
  std::unique_ptr<solver::LeastSquares> guided;
  std::vector<int> guide_rows;         // vertex of each guide constraint
  solver::DenseMatrix guide_weights;   // φ_k at each guide vertex (rows) per handle
  solver::DenseMatrix guide_rest;      // M_c(v') of the guide rows
  solver::DenseMatrix transform_rest;  // M_c(v') of the transformation-constraint rows
  solver::DenseMatrix blend_rest;      // E_T rows (§3.3.3) at the rest state
  solver::DenseMatrix delta;           // D V at the free vertices (Eq. 2.10 rows)
  // Shared-gradient groups (§3.5) in Eq. 2.10/2.11: each group's edges, held to the group's one
  // transformation, and a member whose (shared) M_i gives it.
  int block_F = -1;
  std::vector<std::array<int, 2>> group_edges;
  std::vector<int> group_edge_group, group_probe;
  std::vector<Eigen::Quaterniond> polar_start;  // per free vertex: last frame's R_i (§2.4.4)
  // Eq. 2.8 as X = X_I + Φ C (options.max_basis_columns): X_I the solution for identity
  // transforms, Φ one column per handle parameter, C the parameters' change from identity.
  solver::DenseMatrix at_identity, basis;
  int region_handles = 0, point_handles = 0;

  // Where constrained work vertex v goes, from a rest-side position p.
  Eigen::Vector3d place(const HandleTransforms& transforms, int v, const Eigen::Vector3d& p) const {
    if (w.role[v] == VertexRole::RegionHandle) return apply(transforms.regions[w.handle_of[v]], p);
    if (w.role[v] == VertexRole::PointHandle) return p + transforms.points[w.handle_of[v]];
    return p;
  }

  // Eq. 2.8 in displacements d = ṽ' − v' for these transforms.
  solver::DenseMatrix guide_rhs(const HandleTransforms& transforms) const;
  void pull_back(const solver::DenseMatrix& X, const Vertices& targets, int n0, Vertices& out) const;
  solver::DenseMatrix polar_rhs(const Vertices& X, bool scale, int& fallbacks);
  solver::DenseMatrix second_fixed(const HandleTransforms& transforms) const;
  solver::DenseMatrix group_edge_rhs(const Vertices& X, bool scale) const;

  FirstSystemInput first_input(const HandleTransforms& transforms) const {
    const Vertices& P = w.displaced;
    FirstSystemInput in;
    in.fixed.resize(static_cast<Eigen::Index>(constrained.size()), 3);
    for (size_t k = 0; k < constrained.size(); ++k) {
      const int v = constrained[k];
      in.fixed.row(static_cast<Eigen::Index>(k)) =
          (place(transforms, v, P.row(v).transpose()) - P.row(v).transpose()).transpose();
    }
    // E_L and E_R vanish at the rest state (M_i = I), so their right-hand sides are zero
    // (empty: the solver skips them); only the transformation constraints carry W_c − M_c(v').
    in.rhs.resize(1);
    if (has_coherence) in.rhs.emplace_back();
    if (transform_rest.rows() > 0) {
      solver::DenseMatrix r = -transform_rest;
      for (size_t t = 0; t < transform_vertex.size(); ++t) {
        const int h = transform_handle[t];
        const Eigen::Matrix3d W =
            h < 0 ? Eigen::Matrix3d::Identity() : Eigen::Matrix3d(transforms.regions[h].topLeftCorner<3, 3>());
        // Row a of M_c against coordinate a: block rows 3t + b hold M_c(a, b) in column a.
        r.middleRows(static_cast<Eigen::Index>(3 * t), 3) += W.transpose();
      }
      in.transform_block = static_cast<int>(in.rhs.size());
      in.rhs.push_back(std::move(r));
    }
    // E_T is homogeneous in the positions: in displacements its right-hand side is −A_B v'.
    if (blend_rest.rows() > 0) in.rhs.push_back(-blend_rest);
    return in;
  }

  // Eq. 2.8's blocks (first_system_rows), assembled and factorized.
  void build_first_system(const ImplicitOptions& options, const std::vector<LaplacianBlend>& blends,
                          double blend_weight, const std::vector<std::vector<int>>& shared) {
    const Vertices& P = w.displaced;
    const int n = w.mesh.num_vertices();
    // §2.4.3: the Laplacian of the displaced mesh, so a displaced vertex's δ points along its
    // normal (cotangent weights; uniform ones add the tangential part of Fig. 2.5).
    stencil = w.stencil;
    detail::reweight(stencil, P, w.mesh.F, options.weights);
    const Vertices deltaP = detail::laplacian_coordinates(stencil, P);
    G = detail::gradient_stencils(stencil, P, w.active);
    if (!shared.empty()) detail::share_gradients(G, P, shared, w.active);
    const double h = detail::mean_edge_length(stencil, w.mesh.V);
    detail::FirstSystemRows rows = detail::first_system_rows(w, stencil, G, deltaP, free, constrained, blends);
    transform_vertex = std::move(rows.transform_vertex);
    transform_handle = std::move(rows.transform_handle);
    first = solver::LeastSquares(n);
    weight_R = options.coherence_weight * h * h;
    weight_T = options.transform_weight * h * h;
    // Each block goes to the solver by value, moved (tens of MB at 50K vertices, each page
    // of a copy faulted in afresh).
    first.add_block(std::move(rows.laplacian), 1.0, "E_L (Eq. 2.6)");
    if (rows.coherence.rows() > 0)
      block_R = first.add_block(std::move(rows.coherence), weight_R, "E_R (Eq. 2.7)", std::move(rows.coherence_metric));
    if (rows.transform.rows() > 0)
      block_T = first.add_block(std::move(rows.transform), weight_T, "M_c = W_c (Eq. 2.8)");
    if (rows.blend.rows() > 0) block_B = first.add_block(std::move(rows.blend), blend_weight, "E_T (§3.3.3)");
    first.set_fixed(constrained);
    first.set_ordering_skeleton(detail::edge_graph(stencil));
    has_coherence = block_R >= 0;
    // M_c(v') and E_T's rows at the rest state; no rows when the block is absent.
    const auto at_rest = [&](int block) {
      return block >= 0 ? solver::DenseMatrix(first.block_matrix(block) * solver::DenseMatrix(P))
                        : solver::DenseMatrix(0, 3);
    };
    transform_rest = at_rest(block_T);
    blend_rest = at_rest(block_B);
    first.precompute();
  }

  // Eq. 2.10/2.11 on the undisplaced mesh: the rotations carry the deformation, the rest
  // Laplacian the details.
  void build_second_system(LaplacianWeights weights, const std::vector<std::vector<int>>& shared, double group_weight) {
    const int n = w.mesh.num_vertices();
    detail::Stencil s0 = w.stencil;
    detail::reweight(s0, w.mesh.V, w.mesh.F, weights);
    SparseRows D(n);
    for (int i : free) detail::add_laplacian_row(D, s0, i);
    second = solver::LeastSquares(n);
    second.add_block(D.matrix(), 1.0, "D(v) = R S δ (Eq. 2.10/2.11)");
    if (!shared.empty()) add_group_edges(shared, group_weight);
    second.set_fixed(constrained);
    delta = second.block_matrix(0) * solver::DenseMatrix(w.mesh.V);
    second.precompute();
  }

  // A shared gradient transforms a group's Laplacian coordinates alike, but Eq. 2.10/2.11 would
  // still bend the group with its surroundings through its border; its edges, held to the
  // group's transformation, make it move as one.
  void add_group_edges(const std::vector<std::vector<int>>& shared, double group_weight) {
    const int n = w.mesh.num_vertices();
    std::vector<int> group_of(static_cast<size_t>(n), -1);
    for (size_t f = 0; f < shared.size(); ++f) {
      for (int v : shared[f]) group_of[v] = static_cast<int>(f);
      group_probe.push_back(-1);
    }
    SparseRows E(n);
    for (int i = 0; i < n; ++i) {
      const int f = group_of[i];
      if (f < 0 || !w.active[i]) continue;
      if (group_probe[f] < 0) group_probe[f] = i;
      for (int k = w.stencil.offsets[i]; k < w.stencil.offsets[i + 1]; ++k) {
        const int j = w.stencil.nbr[k];
        if (j <= i || group_of[j] != f) continue;
        E.begin_row();
        E.add(j, 1.0);
        E.add(i, -1.0);
        group_edges.push_back({i, j});
        group_edge_group.push_back(f);
      }
    }
    if (!group_edges.empty())
      block_F = second.add_block(E.matrix(), group_weight, "shared-gradient group edges (§3.5)");
  }

  // X_I and Φ. Parameter column 4h + b of region handle h enters coordinate a with weight
  // T_h(a, b): through the fixed values (p_b, or 1 for the translation b = 3) of the handle's
  // vertices and the transformation rows 3t + b of its constrained vertices (b < 3); column
  // 4·#regions + p is point handle p's translation, through its fixed value.
  void build_basis() {
    const Vertices& P = w.displaced;
    const int q = 4 * region_handles + point_handles;
    HandleTransforms identity;
    identity.regions.assign(static_cast<size_t>(region_handles), Eigen::Matrix4d::Identity());
    identity.points.assign(static_cast<size_t>(point_handles), Eigen::Vector3d::Zero());
    const FirstSystemInput at_rest = first_input(identity);
    at_identity = first.solve(at_rest.rhs, at_rest.fixed);

    FirstSystemInput unit;
    unit.fixed = solver::DenseMatrix::Zero(static_cast<Eigen::Index>(constrained.size()), q);
    for (size_t k = 0; k < constrained.size(); ++k) {
      const int v = constrained[k], h = w.handle_of[v];
      const auto row = static_cast<Eigen::Index>(k);
      if (w.role[v] == VertexRole::RegionHandle) {
        for (int b = 0; b < 3; ++b) unit.fixed(row, 4 * h + b) = P(v, b);
        unit.fixed(row, 4 * h + 3) = 1;
      } else if (w.role[v] == VertexRole::PointHandle) {
        unit.fixed(row, 4 * region_handles + h) = 1;
      }
    }
    unit.rhs.resize(at_rest.rhs.size());  // zero everywhere but the transformation rows
    if (at_rest.transform_block >= 0) {
      solver::DenseMatrix r = solver::DenseMatrix::Zero(transform_rest.rows(), q);
      for (size_t t = 0; t < transform_vertex.size(); ++t)
        if (const int h = transform_handle[t]; h >= 0)
          for (int b = 0; b < 3; ++b) r(static_cast<Eigen::Index>(3 * t + b), 4 * h + b) = 1;
      unit.rhs[static_cast<size_t>(at_rest.transform_block)] = std::move(r);
    }
    basis = first.solve(unit.rhs, unit.fixed);
  }

  // C with X = X_I + Φ C: the parameters' change from the identity transforms.
  solver::DenseMatrix basis_coefficients(const HandleTransforms& transforms) const {
    solver::DenseMatrix C(4 * region_handles + point_handles, 3);
    for (int h = 0; h < region_handles; ++h) {
      Eigen::Matrix<double, 3, 4> change = transforms.regions[static_cast<size_t>(h)].topRows<3>();
      change.leftCols<3>() -= Eigen::Matrix3d::Identity();
      C.middleRows(4 * h, 4) = change.transpose();
    }
    for (int p = 0; p < point_handles; ++p)
      C.row(4 * region_handles + p) = transforms.points[static_cast<size_t>(p)].transpose();
    return C;
  }
};

ImplicitLaplacianDeformer::ImplicitLaplacianDeformer(TriMesh mesh, ImplicitOptions options)
    : Deformer(std::move(mesh)), options_(options) {}

ImplicitLaplacianDeformer::~ImplicitLaplacianDeformer() = default;

void ImplicitLaplacianDeformer::set_options(const ImplicitOptions& options) {
  constexpr const char* fn = "mesh_deform::ImplicitLaplacianDeformer::set_options()";
  if (!(options.degenerate_condition > 1))
    throw InvalidArgument(std::string(fn) + ": degenerate_condition must be > 1");
  if (!(options.s_disp > 0) || !(options.coherence_weight > 0) || !(options.transform_weight > 0) ||
      !(options.guide_weight > 0) || !(options.group_weight > 0))
    throw InvalidArgument(std::string(fn) +
                          ": s_disp, coherence_weight, transform_weight, guide_weight and group_weight must be > 0");
  options_ = options;
  mark_dirty();
}

void ImplicitLaplacianDeformer::set_laplacian_blends(std::vector<LaplacianBlend> blends, double weight) {
  constexpr const char* fn = "mesh_deform::ImplicitLaplacianDeformer::set_laplacian_blends()";
  if (!(weight > 0) || !std::isfinite(weight))
    throw InvalidArgument(std::string(fn) + ": weight must be finite and > 0");
  const int n = mesh_.num_vertices();
  auto in_range = [n](int v) { return v >= 0 && v < n; };
  for (const LaplacianBlend& b : blends) {
    bool ok = in_range(b.vertex);
    for (int k = 0; k < 3; ++k) ok = ok && in_range(b.others[k]) && std::isfinite(b.weights[k]);
    if (!ok)
      throw InvalidArgument(std::string(fn) + ": term at vertex " + std::to_string(b.vertex) +
                            " has a vertex out of range or a weight that is not finite");
  }
  blends_ = std::move(blends);
  blend_weight_ = weight;
  mark_dirty();
}

void ImplicitLaplacianDeformer::set_shared_gradients(std::vector<std::vector<int>> groups) {
  constexpr const char* fn = "mesh_deform::ImplicitLaplacianDeformer::set_shared_gradients()";
  std::vector<int> group_of(static_cast<size_t>(mesh_.num_vertices()), -1);
  for (size_t f = 0; f < groups.size(); ++f) {
    if (groups[f].size() < 4)
      throw InvalidArgument(std::string(fn) + ": group " + std::to_string(f) + " has " +
                            std::to_string(groups[f].size()) + " vertices; a gradient needs at least 4");
    for (int v : groups[f]) {
      if (v < 0 || v >= mesh_.num_vertices())
        throw InvalidArgument(std::string(fn) + ": group " + std::to_string(f) + ": vertex " + std::to_string(v) +
                              " is out of range [0, " + std::to_string(mesh_.num_vertices()) + ")");
      if (group_of[v] >= 0)
        throw InvalidArgument(std::string(fn) + ": vertex " + std::to_string(v) + " is in group " +
                              std::to_string(group_of[v]) + " and in group " + std::to_string(f));
      group_of[v] = static_cast<int>(f);
    }
  }
  shared_ = std::move(groups);
  mark_dirty();
}

std::vector<int> ImplicitLaplacianDeformer::degenerate_vertices() const {
  std::vector<int> out;
  if (!impl_) return out;
  for (int v : impl_->w.moved)
    if (v < mesh_.num_vertices()) out.push_back(v);
  std::sort(out.begin(), out.end());
  return out;
}

void ImplicitLaplacianDeformer::setup(const Layout& layout) {
  const auto t0 = std::chrono::steady_clock::now();
  auto m = std::make_unique<Impl>();
  m->w = detail::build_work_mesh(mesh_, layout, options_);
  const detail::WorkMesh& w = m->w;
  for (int v = 0; v < w.mesh.num_vertices(); ++v)
    (w.role[v] == VertexRole::Free ? m->free : m->constrained).push_back(v);
  m->polar_start.assign(m->free.size(), Eigen::Quaterniond::Identity());
  m->accumulated.assign(static_cast<size_t>(layout.num_region_handles), Eigen::Vector3d::Zero());

  // Eq. 2.10/2.11's system is built and factorized beside Eq. 2.8's: the first system's
  // ordering (nested dissection, CAMD) runs on one core and would leave the other idle. The
  // second reads w, free and constrained and writes only second and delta.
  const auto first = [&] { m->build_first_system(options_, blends_, blend_weight_, shared_); };
  if (options_.shearing == ShearingRemoval::None)
    first();
  else
    solver::side_by_side(first,
                         [&m = *m, this] { m.build_second_system(options_.weights, shared_, options_.group_weight); });

  m->region_handles = layout.num_region_handles;
  m->point_handles = layout.num_point_handles;
  const int parameters = 4 * m->region_handles + m->point_handles;
  if (parameters <= options_.max_basis_columns) m->build_basis();

  report_ = {};
  report_.free_vertices = static_cast<int>(m->free.size());
  report_.degenerate_vertices = w.degenerate;
  report_.inserted_vertices = static_cast<int>(w.inserted.size());
  report_.first_factor_nnz = m->first.factor().report().nnz_L;
  report_.basis_columns = static_cast<int>(m->basis.cols());
  if (options_.shearing != ShearingRemoval::None) report_.second_factor_nnz = m->second.factor().report().nnz_L;
  impl_ = std::move(m);
  report_.setup_ms = ms_since(t0);
}

void ImplicitLaplacianDeformer::build_guide(const std::vector<int>& handles) {
  Impl& m = *impl_;
  const detail::WorkMesh& w = m.w;
  const int n = w.mesh.num_vertices();
  // Smooth fields φ_k, one per region handle: 1 on handle k, 0 on the fixed region and the
  // other handles, min ‖D φ‖² in between (one more factorization, of the small Laplacian
  // system). Σ_k φ_k blends the handles' rotation vectors at each guide vertex, so handles
  // that share a transform impose exactly that transform.
  SparseRows D(n);
  for (int i : m.free) detail::add_laplacian_row(D, m.stencil, i);
  solver::LeastSquares field(n);
  field.add_block(D.matrix(), 1.0, "smooth field");
  field.set_fixed(m.constrained);
  field.precompute();
  const int nh = static_cast<int>(m.accumulated.size());
  solver::DenseMatrix ends = solver::DenseMatrix::Zero(static_cast<Eigen::Index>(m.constrained.size()), nh);
  for (size_t k = 0; k < m.constrained.size(); ++k)
    if (w.role[m.constrained[k]] == VertexRole::RegionHandle) ends(k, w.handle_of[m.constrained[k]]) = 1;
  const solver::DenseMatrix fields = field.solve({solver::DenseMatrix()}, ends);
  std::vector<char> eligible(static_cast<size_t>(n), 0);
  for (int v : m.free) eligible[v] = w.active[v];
  m.guide_rows.clear();
  // Bands across the fields of the handles turned far: there the blend must be pinned down.
  for (int h : handles)
    for (const auto& row : detail::level_bands(m.stencil, fields.col(h), eligible, kGuideLevels)) {
      eligible[row.first] = 0;
      m.guide_rows.push_back(row.first);
    }
  m.guide_weights.resize(static_cast<Eigen::Index>(m.guide_rows.size()), nh);
  for (size_t t = 0; t < m.guide_rows.size(); ++t)
    m.guide_weights.row(static_cast<Eigen::Index>(t)) = fields.row(m.guide_rows[t]);
  SparseRows Gr(n);
  for (int c : m.guide_rows)
    for (int a = 0; a < 3; ++a) {
      Gr.begin_row();
      for (int k = m.G.offsets[c]; k < m.G.offsets[c + 1]; ++k) Gr.add(m.G.vertex[k], m.G.g[k](a));
    }
  const solver::SparseMatrix A_G = Gr.matrix();
  m.guided = std::make_unique<solver::LeastSquares>(n);
  m.guided->add_block(m.first.block_matrix(0), 1.0, "E_L (Eq. 2.6)");
  if (m.block_R >= 0)
    m.guided->add_block(m.first.block_matrix(m.block_R), m.weight_R, "E_R (Eq. 2.7)", m.first.block_metric(m.block_R));
  if (m.block_T >= 0) m.guided->add_block(m.first.block_matrix(m.block_T), m.weight_T, "M_c = W_c (Eq. 2.8)");
  if (m.block_B >= 0) m.guided->add_block(m.first.block_matrix(m.block_B), blend_weight_, "E_T (§3.3.3)");
  m.guided->add_block(A_G, options_.guide_weight * m.weight_T, "guide bands (§2.5)");
  m.guided->set_fixed(m.constrained);
  m.guided->set_ordering_skeleton(detail::edge_graph(m.stencil));
  m.guided->precompute();
  m.guide_rest = A_G * solver::DenseMatrix(w.displaced);
  m.guided_for = handles;
}

// The guide block's right-hand side (large rotations, §2.5's limit): each guide vertex takes the
// φ-blend of the handles' accumulated rotation vectors and log-scales (the fixed region
// contributes the identity with weight 1 − Σ φ_k).
solver::DenseMatrix ImplicitLaplacianDeformer::Impl::guide_rhs(const HandleTransforms& transforms) const {
  solver::DenseMatrix g = -guide_rest;
  const Eigen::VectorXd log_scale = detail::region_log_scales(transforms);
  for (size_t t = 0; t < guide_rows.size(); ++t) {
    Eigen::Vector3d r = Eigen::Vector3d::Zero();
    double ls = 0;
    for (size_t h = 0; h < accumulated.size(); ++h) {
      const double phi = guide_weights(static_cast<Eigen::Index>(t), static_cast<Eigen::Index>(h));
      r += phi * accumulated[h];
      ls += phi * log_scale[static_cast<Eigen::Index>(h)];
    }
    g.middleRows(static_cast<Eigen::Index>(3 * t), 3) += (std::exp(ls) * detail::rotation_of(r)).transpose();
  }
  return g;
}

// The first system's result as the frame (preview, or no shearing removal), with the
// displaced vertices pulled back (§2.4.3): ṽ_i = M_i (v_i − v'_i) + ṽ'_i.
void ImplicitLaplacianDeformer::Impl::pull_back(const solver::DenseMatrix& X, const Vertices& targets, int n0,
                                                Vertices& out) const {
  const Vertices Xv = X;
  const Vertices& P = w.displaced;
  for (int v : free)
    if (v < n0) out.row(v) = Xv.row(v);
  for (int v : w.moved)
    if (v < n0 && w.role[v] == VertexRole::Free)
      out.row(v) = Xv.row(v) + (G.gradient(v, Xv) * (w.mesh.V.row(v) - P.row(v)).transpose()).transpose();
  for (int v : constrained)
    if (v < n0) out.row(v) = targets.row(v);
}

// Shearing removal (§2.4.4): M_i = R_i S_i, s_i = sqrt((λ1² + λ2² + λ3²) / 3) = ‖M_i‖_F / √3;
// the second system's right-hand side s_i R_i δ_i − δ_i per free vertex.
solver::DenseMatrix ImplicitLaplacianDeformer::Impl::polar_rhs(const Vertices& X, bool scale, int& fallbacks) {
  const int nf = static_cast<int>(free.size());
  solver::DenseMatrix rhs(nf, 3);
  fallbacks = core::parallel_sum<int>(0, nf, detail::kVertexChunk, [&](std::ptrdiff_t lo, std::ptrdiff_t hi) {
    int fell = 0;
    for (std::ptrdiff_t k = lo; k < hi; ++k) {
      const int v = free[static_cast<size_t>(k)];
      const Eigen::Matrix3d M = G.gradient(v, X);
      bool fell_back = false;
      // Frames of a drag differ little: last frame's rotation starts the fit (rotation_fit.h).
      const Eigen::Matrix3d R = detail::nearest_rotation(M, polar_start[static_cast<size_t>(k)], &fell_back);
      fell += fell_back;
      const double s_i = scale ? M.norm() / std::sqrt(3.0) : 1.0;
      const Eigen::Vector3d d = delta.row(k).transpose();
      rhs.row(k) = (s_i * (R * d) - d).transpose();
    }
    return fell;
  });
  return rhs;
}

// Each group edge's displacement difference under the group's transformation (s) R, from its
// shared M_i at X: (s R − I)(v_j − v_i).
solver::DenseMatrix ImplicitLaplacianDeformer::Impl::group_edge_rhs(const Vertices& X, bool scale) const {
  std::vector<Eigen::Matrix3d> change(group_probe.size(), Eigen::Matrix3d::Zero());
  for (size_t f = 0; f < group_probe.size(); ++f) {
    if (group_probe[f] < 0) continue;
    const Eigen::Matrix3d M = G.gradient(group_probe[f], X);
    const Eigen::Matrix3d R = geometry::polar_rotation(M);
    change[f] = (scale ? M.norm() / std::sqrt(3.0) : 1.0) * R - Eigen::Matrix3d::Identity();
  }
  solver::DenseMatrix rhs(static_cast<Eigen::Index>(group_edges.size()), 3);
  for (size_t e = 0; e < group_edges.size(); ++e) {
    const auto [i, j] = group_edges[e];
    rhs.row(static_cast<Eigen::Index>(e)) =
        (change[group_edge_group[e]] * (w.mesh.V.row(j) - w.mesh.V.row(i)).transpose()).transpose();
  }
  return rhs;
}

// The second system's constrained displacements: each constrained vertex where its handle puts it.
solver::DenseMatrix ImplicitLaplacianDeformer::Impl::second_fixed(const HandleTransforms& transforms) const {
  solver::DenseMatrix fixed(constrained.size(), 3);
  for (size_t k = 0; k < constrained.size(); ++k) {
    const int v = constrained[k];
    const Eigen::Vector3d r = w.mesh.V.row(v).transpose();
    fixed.row(k) = (place(transforms, v, r) - r).transpose();
  }
  return fixed;
}

void ImplicitLaplacianDeformer::solve(const HandleTransforms& transforms, const Vertices& targets, Vertices& out) {
  const auto t_frame = std::chrono::steady_clock::now();
  Impl& m = *impl_;
  const detail::WorkMesh& w = m.w;
  const int n0 = mesh_.num_vertices();
  const Vertices& P = w.displaced;

  auto t0 = std::chrono::steady_clock::now();
  // Large rotations: continue each handle's angle from the previous frame (§2.5's limit).
  std::vector<int> big;
  for (size_t h = 0; h < m.accumulated.size(); ++h) {
    const Eigen::Matrix3d L = transforms.regions[h].topLeftCorner<3, 3>();
    m.accumulated[h] = detail::unwrap_rotation(geometry::polar_rotation(L), m.accumulated[h]);
    if (options_.large_rotations && m.accumulated[h].norm() > options_.guide_angle) big.push_back(static_cast<int>(h));
  }
  report_.guided = !big.empty();
  solver::DenseMatrix X;
  if (big.empty() && m.basis.cols() > 0) {
    X = solver::DenseMatrix(P) + m.at_identity;
    const solver::DenseMatrix c = m.basis_coefficients(transforms);
    core::parallel_for(0, X.rows(), detail::kVertexChunk, [&](std::ptrdiff_t lo, std::ptrdiff_t hi) {
      X.middleRows(lo, hi - lo).noalias() += m.basis.middleRows(lo, hi - lo) * c;
    });
  } else if (big.empty()) {
    const FirstSystemInput in = m.first_input(transforms);
    X = solver::DenseMatrix(P) + m.first.solve(in.rhs, in.fixed, options_.refinement_steps);
  } else {
    FirstSystemInput in = m.first_input(transforms);
    if (big != m.guided_for) build_guide(big);
    in.rhs.push_back(m.guide_rhs(transforms));
    X = solver::DenseMatrix(P) + m.guided->solve(in.rhs, in.fixed, options_.refinement_steps);
  }
  report_.first_solve_ms = ms_since(t0);

  if (options_.shearing == ShearingRemoval::None || preview_) {
    m.pull_back(X, targets, n0, out);
    report_.polar_ms = report_.second_solve_ms = 0;
    report_.frame_ms = ms_since(t_frame);
    return;
  }

  t0 = std::chrono::steady_clock::now();  // shearing removal (§2.4.4)
  const solver::DenseMatrix rhs2 =
      m.polar_rhs(Vertices(X), options_.shearing == ShearingRemoval::ScaleFeatures, report_.polar_fallbacks);
  report_.polar_ms = ms_since(t0);

  t0 = std::chrono::steady_clock::now();
  std::vector<solver::DenseMatrix> rhs_blocks{rhs2};
  if (m.block_F >= 0)
    rhs_blocks.push_back(m.group_edge_rhs(Vertices(X), options_.shearing == ShearingRemoval::ScaleFeatures));
  const solver::DenseMatrix Y = m.second.solve(rhs_blocks, m.second_fixed(transforms), options_.refinement_steps);
  for (int v : m.free)
    if (v < n0) out.row(v) = w.mesh.V.row(v) + Y.row(v);
  report_.second_solve_ms = ms_since(t0);
  report_.frame_ms = ms_since(t_frame);
}

}  // namespace lapis::mesh_deform
