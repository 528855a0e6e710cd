#include "lapis/mesh_deform/edge_laplacian.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "cell_fit.h"
#include "edge_cell_sums.h"
#include "handle_rotation_blend.h"
#include "lapis/core/parallel_for.h"
#include "lapis/solver/least_squares.h"
#include "laplacian_cells.h"
#include "sparse_rows.h"
#include "stencil.h"

namespace lapis::mesh_deform {
namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// A vertex of a part of the unknowns (connected through the mesh's edges) that no constrained
// vertex and no soft handle row holds, or -1. Such a part can translate freely: DᵀD is
// singular there, yet its factorization may only meet a tiny pivot and succeed.
int first_unanchored(const detail::Stencil& s, const std::vector<char>& unknown, const std::vector<char>& soft) {
  const int n = s.size();
  std::vector<char> seen(static_cast<size_t>(n), 0);
  std::vector<int> stack;
  for (int start = 0; start < n; ++start) {
    if (!unknown[static_cast<size_t>(start)] || seen[static_cast<size_t>(start)]) continue;
    bool anchored = false;
    stack.assign(1, start);
    seen[static_cast<size_t>(start)] = 1;
    while (!stack.empty()) {
      const int i = stack.back();
      stack.pop_back();
      anchored = anchored || soft[static_cast<size_t>(i)];
      for (int k = s.offsets[i]; k < s.offsets[i + 1]; ++k) {
        const int j = s.nbr[k];
        if (!unknown[static_cast<size_t>(j)]) {
          anchored = true;
        } else if (!seen[static_cast<size_t>(j)]) {
          seen[static_cast<size_t>(j)] = 1;
          stack.push_back(j);
        }
      }
    }
    if (!anchored) return start;
  }
  return -1;
}

constexpr const char* kUndetermined =
    "mesh_deform::EdgeLaplacianDeformer::precompute(): the Laplacian rows do not determine the free vertices (is "
    "some part of the ROI not connected to a handle or the fixed region?)";

}  // namespace

// Eq. 6 solved for displacements from the rest mesh: the right-hand side of a node's row is
// (T − I) δ, exactly zero for T = I, so the identity frame returns the rest mesh exactly.
// D has a row for every node whose row touches an unknown (literal Eq. 6 without the rows
// that are constant); DᵀD (+ soft rows) is factorized once per selection.
struct EdgeLaplacianDeformer::Impl {
  // Vertices in spatial order (detail::spatial_order), as in ARAP: the fits and the
  // right-hand sides gather along rows of neighbouring vertices, and a Loop-subdivided mesh's
  // own order puts half of every ring #V/2 entries away.
  std::vector<int> order;        // internal index -> mesh vertex
  Vertices rest;                 // rest positions, internal order
  detail::LaplacianCells cells;  // every node of the mesh
  std::vector<int> rows;         // nodes with a row, in row order
  std::vector<char> unknown;     // #V
  std::vector<int> soft;         // soft handle vertices, one position row each
  solver::LeastSquares ls{1};
  solver::DenseMatrix delta;                 // #rows by 3: rest Laplacian vectors
  std::vector<detail::RestCell> rest_cells;  // #rows
  std::vector<detail::CellState> state;      // #rows
  // Edge domain: the cells' A from ring sums (edge_cell_sums.h), with each row's ω.
  detail::Stencil stencil;
  std::unique_ptr<detail::EdgeCellSums> sums;
  std::vector<double> row_omega;
  bool have_previous = false;  // state holds the transforms of the last frame's result
  // #rows by #region handles: each handle's harmonic field at the row's node (the mean of its
  // edge's ends in the edge domain), the weights of ColdStart::HandleRotations.
  solver::DenseMatrix node_fields;

  void build_node_fields(const Layout& layout, const std::vector<int>& fixed);
  void start_from_handles(const HandleTransforms& transforms, bool scale);

  solver::DenseMatrix solve_with_transforms(const Vertices& rest, const solver::DenseMatrix& fixed,
                                            const solver::DenseMatrix& soft_rhs) const;
  int fit(const Vertices& rest, const Vertices& X, CellTransform transform, ScaleFrame frame);
};

// One back-substitution of 3 right-hand sides with the current transforms; the displacement.
solver::DenseMatrix EdgeLaplacianDeformer::Impl::solve_with_transforms(const Vertices&,
                                                                       const solver::DenseMatrix& fixed,
                                                                       const solver::DenseMatrix& soft_rhs) const {
  solver::DenseMatrix b(static_cast<Eigen::Index>(rows.size()), 3);
  detail::for_vertices(rows.size(), [&](std::ptrdiff_t r) {
    const Eigen::Vector3d d = delta.row(r).transpose();
    b.row(r) = (state[static_cast<size_t>(r)].T * d - d).transpose();
  });
  std::vector<solver::DenseMatrix> rhs{std::move(b)};
  if (!soft.empty()) rhs.push_back(soft_rhs);
  return ls.solve(rhs, fixed);
}

// φ_h with Dᵀ D φ_h = 0 (the same factor): 1 on handle h, 0 on every other constrained vertex.
void EdgeLaplacianDeformer::Impl::build_node_fields(const Layout& layout, const std::vector<int>& fixed) {
  const int nh = layout.num_region_handles;
  auto indicator = [&](const std::vector<int>& vertices) {
    solver::DenseMatrix e = solver::DenseMatrix::Zero(static_cast<Eigen::Index>(vertices.size()), nh);
    for (size_t k = 0; k < vertices.size(); ++k) {
      const int v = order[static_cast<size_t>(vertices[k])];
      if (layout.role[v] == VertexRole::RegionHandle) e(static_cast<Eigen::Index>(k), layout.handle_of[v]) = 1;
    }
    return e;
  };
  const solver::DenseMatrix ends = indicator(fixed);
  std::vector<solver::DenseMatrix> rhs{solver::DenseMatrix()};
  if (!soft.empty()) rhs.push_back(indicator(soft));
  solver::DenseMatrix phi = ls.solve(rhs, ends);
  for (size_t k = 0; k < fixed.size(); ++k) phi.row(fixed[k]) = ends.row(static_cast<Eigen::Index>(k));
  node_fields.resize(static_cast<Eigen::Index>(rows.size()), nh);
  for (size_t r = 0; r < rows.size(); ++r) {
    const int a = rows[r];
    if (cells.ends.empty())
      node_fields.row(static_cast<Eigen::Index>(r)) = phi.row(a);
    else
      node_fields.row(static_cast<Eigen::Index>(r)) = 0.5 * (phi.row(cells.ends[a][0]) + phi.row(cells.ends[a][1]));
  }
}

// Every node's T as the φ-blend of the handles' rotation vectors and (with scale) log-scales;
// the fixed region counts as the identity.
void EdgeLaplacianDeformer::Impl::start_from_handles(const HandleTransforms& transforms, bool scale) {
  const std::vector<Eigen::Vector3d> r = detail::region_rotation_vectors(transforms);
  const Eigen::VectorXd log_scale =
      scale ? detail::region_log_scales(transforms) : Eigen::VectorXd::Zero(static_cast<Eigen::Index>(r.size()));
  detail::for_vertices(rows.size(), [&](std::ptrdiff_t k) {
    detail::CellState& st = state[static_cast<size_t>(k)];
    st.q1 = detail::blended_rotation(node_fields.row(k), r);
    st.q2.setIdentity();
    st.T = std::exp(node_fields.row(k).dot(log_scale)) * st.q1.toRotationMatrix();
  });
}

// Every row's T fitted to its cell on X (Eq. 7–8, one node per task); negative weights count
// as 0 here (an energy with negative weights has no minimum). Returns the SVD fallbacks.
int EdgeLaplacianDeformer::Impl::fit(const Vertices& rest, const Vertices& X, CellTransform transform,
                                     ScaleFrame frame) {
  const double c2 = cells.c * cells.c;
  if (sums) sums->update(X);
  auto cell_matrix = [&](std::ptrdiff_t r) -> Eigen::Matrix3d {
    const int a = rows[static_cast<size_t>(r)];
    if (sums) {
      const auto [i, j] = cells.ends[static_cast<size_t>(a)];
      return c2 * row_omega[static_cast<size_t>(r)] * sums->fans(i, j, X);
    }
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
    for (int k = cells.offsets[a]; k < cells.offsets[a + 1]; ++k) {
      const double w = std::max(cells.w[k], 0.0);
      const int p = cells.p[k], q = cells.q[k];
      A.noalias() += (w * (X.row(p) - X.row(q)).transpose()) * (rest.row(p) - rest.row(q));
    }
    return c2 * A;
  };
  auto fit_range = [&](std::ptrdiff_t lo, std::ptrdiff_t hi) {
    int fell = 0;
    for (std::ptrdiff_t r = lo; r < hi; ++r)
      fell += detail::fit_cell(cell_matrix(r), rest_cells[static_cast<size_t>(r)], transform, frame,
                               state[static_cast<size_t>(r)]);
    return fell;
  };
  return core::parallel_sum<int>(0, static_cast<std::ptrdiff_t>(rows.size()), detail::kVertexChunk, fit_range);
}

EdgeLaplacianDeformer::EdgeLaplacianDeformer(TriMesh mesh, EdgeLaplacianOptions options) : Deformer(std::move(mesh)) {
  set_options(options);
}
EdgeLaplacianDeformer::~EdgeLaplacianDeformer() = default;

void EdgeLaplacianDeformer::set_options(const EdgeLaplacianOptions& o) {
  const char* fn = "mesh_deform::EdgeLaplacianDeformer::set_options(): ";
  if (o.iterations < 1)
    throw InvalidArgument(fn + std::string("iterations = ") + std::to_string(o.iterations) + ", expected >= 1");
  if (!(o.tolerance >= 0) || !std::isfinite(o.tolerance))
    throw InvalidArgument(fn + std::string("tolerance must be finite and >= 0"));
  if (!(o.handle_weight > 0) || !std::isfinite(o.handle_weight))
    throw InvalidArgument(fn + std::string("handle_weight must be finite and > 0"));
  // Only what setup() builds from invalidates it; the fit mode and the iteration do not.
  const EdgeLaplacianOptions& p = options_;
  if (o.domain != p.domain || o.weights != p.weights || o.frame != p.frame || o.soft_handles != p.soft_handles ||
      o.handle_weight != p.handle_weight)
    mark_dirty();
  options_ = o;
}

void EdgeLaplacianDeformer::reset_warm_start() {
  if (impl_) impl_->have_previous = false;
}

void EdgeLaplacianDeformer::setup(const Layout& layout) {
  const auto t0 = std::chrono::steady_clock::now();
  auto m = std::make_unique<Impl>();
  const int n = mesh_.num_vertices();
  m->order = detail::spatial_order(mesh_.V);
  const std::vector<int> rank = detail::rank_in(m->order);
  m->rest = mesh_.V(m->order, Eigen::all);
  geometry::Faces F = mesh_.F;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c) F(f, c) = rank[static_cast<size_t>(F(f, c))];
  const Vertices& rest = m->rest;
  m->stencil = detail::make_stencil(rest, F, options_.weights);
  const detail::Stencil& stencil = m->stencil;
  const bool edges = options_.domain == LaplacianDomain::Edges;
  m->cells = edges ? detail::edge_cells(stencil, options_.weights) : detail::vertex_cells(stencil);
  m->unknown.assign(static_cast<size_t>(n), 0);
  std::vector<int> fixed;
  detail::SparseRows H(n);
  for (int i = 0; i < n; ++i) {
    const VertexRole r = layout.role[static_cast<size_t>(m->order[static_cast<size_t>(i)])];
    const bool unknown = r == VertexRole::Free || (options_.soft_handles && r != VertexRole::Fixed);
    m->unknown[static_cast<size_t>(i)] = unknown;
    if (!unknown) {
      fixed.push_back(i);
    } else if (r != VertexRole::Free) {
      m->soft.push_back(i);
      H.begin_row();
      H.add(i, 1.0);
    }
  }
  const detail::LaplacianCells& c = m->cells;
  for (int a = 0; a < c.num_nodes(); ++a)
    for (int k = c.offsets[a]; k < c.offsets[a + 1]; ++k)
      if (m->unknown[static_cast<size_t>(c.p[k])] || m->unknown[static_cast<size_t>(c.q[k])]) {
        m->rows.push_back(a);
        break;
      }
  m->ls = solver::LeastSquares(n);
  m->ls.add_block(detail::laplacian_rows(c, m->rows, n), 1.0, "D(v') = T δ (Eq. 6)");
  if (!m->soft.empty()) m->ls.add_block(H.matrix(), options_.handle_weight, "soft handles (Eq. 6)");
  m->ls.set_fixed(fixed);
  // DᵀD couples vertices three rings apart (edge domain) or two: ordered on the mesh's own
  // separators, its factor has about a tenth fewer non-zeros than with CHOLMOD's choice, and
  // the analysis takes half the time.
  m->ls.set_ordering_skeleton(detail::edge_graph(stencil));
  std::vector<char> is_soft(static_cast<size_t>(n), 0);
  for (int v : m->soft) is_soft[static_cast<size_t>(v)] = 1;
  if (const int v = first_unanchored(stencil, m->unknown, is_soft); v >= 0)
    throw NotPositiveDefinite(std::string(kUndetermined) + ": vertex " +
                                  std::to_string(m->order[static_cast<size_t>(v)]) + " and its part move freely",
                              m->order[static_cast<size_t>(v)]);
  try {
    m->ls.precompute();
  } catch (const NotPositiveDefinite& e) {
    throw NotPositiveDefinite(std::string(kUndetermined) + ": " + e.what(),
                              e.column() >= 0 ? m->order[static_cast<size_t>(e.column())] : -1);
  }
  const Vertices all_delta = detail::laplacian_vectors(c, rest);
  const int nr = static_cast<int>(m->rows.size());
  m->delta.resize(nr, 3);
  m->rest_cells.resize(static_cast<size_t>(nr));
  m->state.assign(static_cast<size_t>(nr), detail::CellState{});
  const bool principal = options_.frame == ScaleFrame::RestPrincipal;
  detail::for_vertices(static_cast<size_t>(nr), [&](std::ptrdiff_t r) {
    const int a = m->rows[static_cast<size_t>(r)];
    m->delta.row(r) = all_delta.row(a);
    Eigen::Matrix3d C0 = Eigen::Matrix3d::Zero();
    for (int k = c.offsets[a]; k < c.offsets[a + 1]; ++k) {
      const Eigen::Vector3d e = c.c * (rest.row(c.p[k]) - rest.row(c.q[k])).transpose();
      C0.noalias() += std::max(c.w[k], 0.0) * e * e.transpose();
    }
    m->rest_cells[static_cast<size_t>(r)] = detail::rest_cell(C0, principal);
  });
  if (edges) {
    // Uniform: every entry of a node carries its ω and the fans unit weights; cotangent: the
    // fans carry the (clamped) weights of the neighbouring edges, as edge_cells() does.
    const bool uniform = options_.weights == LaplacianWeights::Uniform;
    std::vector<double> u(stencil.w.size());
    for (size_t k = 0; k < u.size(); ++k) u[k] = uniform ? 1.0 : std::max(stencil.w[k], 0.0);
    m->sums = std::make_unique<detail::EdgeCellSums>(m->stencil, std::move(u), m->rest);
    m->row_omega.resize(static_cast<size_t>(nr));
    for (int r = 0; r < nr; ++r) {
      const int a = m->rows[static_cast<size_t>(r)];
      m->row_omega[static_cast<size_t>(r)] = uniform ? c.w[static_cast<size_t>(c.offsets[a])] : 1.0;
    }
  }
  m->build_node_fields(layout, fixed);
  impl_ = std::move(m);
  report_ = {};
  report_.nodes = report_.rows = nr;
  report_.unknowns = n - static_cast<int>(fixed.size());
  report_.factor_nnz = static_cast<long>(impl_->ls.factor().report().nnz_L);
  report_.setup_ms = ms_since(t0);
}

// A naive solve (T = I) or, warm, one with the last frame's transforms places the free
// vertices; then each iteration fits every T on the current positions and solves again
// (§4: "three to four iterations for calculating the rotation and scale matrices and
// updating the new positions").
void EdgeLaplacianDeformer::solve(const HandleTransforms& transforms, const Vertices& mesh_targets, Vertices& out) {
  const auto t_frame = std::chrono::steady_clock::now();
  Impl& m = *impl_;
  const Vertices& rest = m.rest;
  const Vertices targets = mesh_targets(m.order, Eigen::all);
  const std::vector<int>& fixed_ids = m.ls.fixed();
  solver::DenseMatrix fixed(static_cast<Eigen::Index>(fixed_ids.size()), 3);
  for (size_t k = 0; k < fixed_ids.size(); ++k) fixed.row(k) = targets.row(fixed_ids[k]) - rest.row(fixed_ids[k]);
  solver::DenseMatrix soft_rhs(static_cast<Eigen::Index>(m.soft.size()), 3);
  for (size_t k = 0; k < m.soft.size(); ++k) soft_rhs.row(k) = targets.row(m.soft[k]) - rest.row(m.soft[k]);
  if (!(options_.warm_start && m.have_previous)) {
    if (options_.cold_start == ColdStart::Identity)
      for (auto& s : m.state) s = detail::CellState{};
    else
      m.start_from_handles(transforms, options_.transform != CellTransform::Rotation);
  }

  double fit_ms = 0, solve_ms = 0, move = 0;
  int fallbacks = 0, it = 0;
  const double diag = (rest.colwise().maxCoeff() - rest.colwise().minCoeff()).norm();
  Vertices X = targets;  // constrained vertices exactly on their targets
  auto place = [&](const solver::DenseMatrix& d) {
    double largest = 0;
    for (Eigen::Index i = 0; i < rest.rows(); ++i) {
      if (!m.unknown[static_cast<size_t>(i)]) continue;
      const Eigen::RowVector3d x = rest.row(i) + d.row(i);
      largest = std::max(largest, (x - X.row(i)).norm());
      X.row(i) = x;
    }
    return largest;
  };
  auto t0 = std::chrono::steady_clock::now();
  place(m.solve_with_transforms(rest, fixed, soft_rhs));
  solve_ms += ms_since(t0);
  while (it < options_.iterations) {
    t0 = std::chrono::steady_clock::now();
    fallbacks += m.fit(rest, X, options_.transform, options_.frame);
    fit_ms += ms_since(t0);
    t0 = std::chrono::steady_clock::now();
    move = place(m.solve_with_transforms(rest, fixed, soft_rhs));
    solve_ms += ms_since(t0);
    ++it;
    if (options_.tolerance > 0 && move <= options_.tolerance * diag) break;
  }
  out.resize(X.rows(), 3);
  out(m.order, Eigen::all) = X;
  m.have_previous = true;
  report_.iterations = it;
  report_.last_move = move;
  report_.rotation_fallbacks = fallbacks;
  report_.fit_ms = fit_ms;
  report_.solve_ms = solve_ms;
  report_.frame_ms = ms_since(t_frame);
}

}  // namespace lapis::mesh_deform
