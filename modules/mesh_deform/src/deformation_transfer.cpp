#include "lapis/mesh_deform/deformation_transfer.h"

#include <chrono>
#include <limits>
#include <string>

#include <Eigen/Cholesky>

#include "isoline_basis.h"
#include "lapis/geometry/connectivity.h"
#include "lapis/geometry/polar.h"
#include "lapis/solver/least_squares.h"

namespace lapis::mesh_deform {
namespace {

using solver::DenseMatrix;
constexpr const char* kFn = "mesh_deform::DeformationTransfer";

[[noreturn]] void fail(const std::string& what) { throw InvalidArgument(std::string(kFn) + ": " + what); }

// One mesh's isolines seen from its edges: W_e of Eq. 11/12, row e = Σ c_ℓ ēᵀ at block ℓ, the
// edge taking the mean field of its ends.
struct EdgeBasis {
  HandleSets sets;
  int sets_k = 0, isolines = 0;
  std::vector<std::array<int, 2>> edges;
  std::vector<detail::IsolineBracket> bracket;  // #E · K
  Vertices rest;                                // #E by 3 rest edge vectors
  Eigen::MatrixX3d centroids;                   // per handle, rest

  int count() const { return sets_k * isolines; }

  // Row e of W_e times R (3m by 3, block ℓ = r_ℓᵀ).
  Eigen::RowVector3d edge(int e, const DenseMatrix& R) const {
    Eigen::RowVector3d d = Eigen::RowVector3d::Zero();
    for (int i = 0; i < sets_k; ++i) {
      const detail::IsolineBracket& b = bracket[e * sets_k + i];
      d += rest.row(e) * (b.w0 * R.middleRows<3>(3 * b.lower) + b.w1 * R.middleRows<3>(3 * b.lower + 3));
    }
    return d;
  }
};

EdgeBasis make_edge_basis(const TriMesh& mesh, const Selection& sel, const TransferOptions& o) {
  EdgeBasis b;
  const Layout layout = make_layout(sel, mesh.num_vertices(), kFn);
  b.sets = handle_sets(mesh, layout, sel, o.fields);
  const Eigen::MatrixXd phi = harmonic_fields(mesh, b.sets).phi;
  b.sets_k = b.sets.size() == 2 ? 1 : b.sets.size();
  b.isolines = o.isolines;
  b.edges = geometry::Connectivity(mesh).edges();
  b.rest.resize(static_cast<Eigen::Index>(b.edges.size()), 3);
  b.bracket.resize(b.edges.size() * b.sets_k);
  for (size_t e = 0; e < b.edges.size(); ++e) {
    const auto [u, v] = b.edges[e];
    b.rest.row(e) = mesh.V.row(v) - mesh.V.row(u);
    for (int i = 0; i < b.sets_k; ++i) {
      const int c = detail::field_of_set(b.sets_k, i);
      const double f = 0.5 * (phi(u, c) + phi(v, c));  // the edge's field: its ends' mean
      b.bracket[e * b.sets_k + i] = detail::isoline_bracket(f, b.sets_k == 1 ? 1.0 : f, i, b.isolines);
    }
  }
  b.centroids.resize(b.sets.size(), 3);
  for (int h = 0; h < b.sets.size(); ++h) {
    Eigen::RowVector3d c = Eigen::RowVector3d::Zero();
    for (int v : b.sets.handle_vertices[h]) c += mesh.V.row(v);
    b.centroids.row(h) = c / static_cast<double>(b.sets.handle_vertices[h].size());
  }
  return b;
}

// Σ_e w_eᵀ w_e of Eq. 11's normal equations (3m by 3m).
DenseMatrix edge_normal_matrix(const EdgeBasis& b) {
  const int m = b.count();
  DenseMatrix A = DenseMatrix::Zero(3 * m, 3 * m);
  for (size_t e = 0; e < b.edges.size(); ++e) {
    const Eigen::Matrix3d ee = b.rest.row(e).transpose() * b.rest.row(e);
    for (int i = 0; i < b.sets_k; ++i)
      for (int k = 0; k < b.sets_k; ++k) {
        const auto& p = b.bracket[e * b.sets_k + i];
        const auto& q = b.bracket[e * b.sets_k + k];
        const int lp[2] = {p.lower, p.lower + 1}, lq[2] = {q.lower, q.lower + 1};
        const double wp[2] = {p.w0, p.w1}, wq[2] = {q.w0, q.w1};
        for (int s = 0; s < 2; ++s)
          for (int t = 0; t < 2; ++t) A.block<3, 3>(3 * lp[s], 3 * lq[t]) += wp[s] * wq[t] * ee;
      }
  }
  return A;
}

// The sparse vertex-edge difference matrix E (#E by #V): row e is x_v − x_u.
solver::SparseMatrix difference_matrix(const std::vector<std::array<int, 2>>& edges, int n) {
  std::vector<Eigen::Triplet<double>> t;
  for (size_t e = 0; e < edges.size(); ++e)
    t.emplace_back(static_cast<int>(e), edges[e][0], -1.0), t.emplace_back(static_cast<int>(e), edges[e][1], 1.0);
  solver::SparseMatrix E(static_cast<int>(edges.size()), n);
  E.setFromTriplets(t.begin(), t.end());
  return E;
}

// One vertex per connected component (the one nearest `anchor`) and every isolated vertex:
// Eq. 12 sees only edge vectors, so each part needs one position.
std::vector<int> pinned_vertices(const TriMesh& mesh, const Eigen::Vector3d& anchor) {
  const auto comps = geometry::connected_components(mesh);
  std::vector<int> best(static_cast<size_t>(comps.count), -1), pins;
  std::vector<double> dist(static_cast<size_t>(comps.count), std::numeric_limits<double>::infinity());
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const int c = comps.vertex_component[v];
    if (c < 0) {
      pins.push_back(v);
      continue;
    }
    const double d = (mesh.V.row(v).transpose() - anchor).squaredNorm();
    if (d < dist[c]) dist[c] = d, best[c] = v;
  }
  for (int v : best)
    if (v >= 0) pins.push_back(v);
  std::sort(pins.begin(), pins.end());
  return pins;
}

// Before any field is solved. The ROI's complement is the fixed region.
void require_matching(const Selection& s, int ns, const Selection& t, int nt) {
  const bool fs = static_cast<int>(s.roi.size()) < ns, ft = static_cast<int>(t.roi.size()) < nt;
  auto counts = [](const Selection& x, bool fixed) {
    return std::to_string(x.region_handles.size()) + " region and " + std::to_string(x.point_handles.size()) +
           " point handles " + (fixed ? "and a fixed region" : "and no fixed region");
  };
  if (s.region_handles.size() != t.region_handles.size() || s.point_handles.size() != t.point_handles.size() ||
      fs != ft)
    fail("the handles do not correspond: the source has " + counts(s, fs) + ", the target " + counts(t, ft) +
         " (paired one to one, in order)");
}

}  // namespace

struct DeformationTransfer::Impl {
  TriMesh source, target;
  EdgeBasis src, tgt;
  Eigen::LDLT<DenseMatrix> eq11;
  solver::LeastSquares eq12{1};
  geometry::Similarity3 frame;  // source frame -> target frame
  std::vector<int> pins;
};

DeformationTransfer::DeformationTransfer(const TriMesh& source, const Selection& source_handles, const TriMesh& target,
                                         const Selection& target_handles, TransferOptions options)
    : impl_(std::make_unique<Impl>()) {
  const auto t0 = std::chrono::steady_clock::now();
  if (options.isolines < 2) fail("isolines = " + std::to_string(options.isolines) + ", expected >= 2");
  require_matching(source_handles, source.num_vertices(), target_handles, target.num_vertices());
  Impl& m = *impl_;
  m.source = source;
  m.target = target;
  m.src = make_edge_basis(source, source_handles, options);
  m.tgt = make_edge_basis(target, target_handles, options);

  DenseMatrix A = edge_normal_matrix(m.src);
  const double ridge = 1e-10 * A.trace() / A.rows();  // isolines no edge reaches keep the identity
  A.diagonal().array() += ridge;
  m.eq11.compute(A);
  // Handle centroids give the frames' similarity once they span a plane.
  if (m.src.sets.size() >= 3) m.frame = geometry::fit_similarity(m.src.centroids, m.tgt.centroids);
  m.pins = pinned_vertices(target, m.tgt.centroids.row(0).transpose());
  m.eq12 = solver::LeastSquares(target.num_vertices());
  m.eq12.add_block(difference_matrix(m.tgt.edges, target.num_vertices()), 1.0, "Eq. 12");
  m.eq12.set_fixed(m.pins);
  m.eq12.precompute();
  report_.handles = m.src.sets.size();
  report_.unknowns = 3 * m.src.count();
  report_.pinned = m.pins;
  report_.setup_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

DeformationTransfer::~DeformationTransfer() = default;

Vertices DeformationTransfer::transfer(const Vertices& X) {
  Impl& m = *impl_;
  if (X.rows() != m.source.num_vertices() || !X.allFinite())
    fail("transfer(): the deformed source must be " + std::to_string(m.source.num_vertices()) +
         " finite positions, got " + std::to_string(X.rows()) + " rows");
  const int mm = m.src.count();
  // Eq. 11: W_e R_e = E X in least squares, with a ridge toward the identity, solved for
  // R − I: the ridge makes the system as ill-conditioned as 1e10 along isolines few edges
  // reach, and this way what it amplifies is the rounding of the deformation, not of the
  // identity (which then comes back exactly at rest).
  const DenseMatrix identity = DenseMatrix::Identity(3, 3).replicate(mm, 1);
  DenseMatrix rhs = DenseMatrix::Zero(3 * mm, 3);
  Vertices D(m.src.edges.size(), 3);
  for (size_t e = 0; e < m.src.edges.size(); ++e) {
    D.row(e) = X.row(m.src.edges[e][1]) - X.row(m.src.edges[e][0]);
    const Eigen::RowVector3d deviation = D.row(e) - m.src.edge(static_cast<int>(e), identity);
    const Eigen::Matrix3d ed = m.src.rest.row(e).transpose() * deviation;
    for (int i = 0; i < m.src.sets_k; ++i) {
      const auto& b = m.src.bracket[e * m.src.sets_k + i];
      rhs.middleRows<3>(3 * b.lower) += b.w0 * ed;
      rhs.middleRows<3>(3 * b.lower + 3) += b.w1 * ed;
    }
  }
  const DenseMatrix R = identity + m.eq11.solve(rhs);
  double fit = 0, ref = 0;
  for (size_t e = 0; e < m.src.edges.size(); ++e)
    fit += (m.src.edge(static_cast<int>(e), R) - D.row(e)).squaredNorm(), ref += D.row(e).squaredNorm();
  report_.eq11_residual = ref > 0 ? std::sqrt(fit / ref) : 0;

  // Into the target's frame: r ↦ Q r Qᵀ (blocks hold rᵀ).
  DenseMatrix Rt = R;
  const Eigen::Matrix3d& Q = m.frame.R;
  for (int l = 0; l < mm; ++l) Rt.middleRows<3>(3 * l) = Q * R.middleRows<3>(3 * l) * Q.transpose();
  // Eq. 12: E X_tgt = W_e^tgt R_e, the pinned vertices moved with handle 0.
  Vertices target_edges(m.tgt.edges.size(), 3);
  for (size_t e = 0; e < m.tgt.edges.size(); ++e) target_edges.row(e) = m.tgt.edge(static_cast<int>(e), Rt);
  Eigen::RowVector3d c0 = Eigen::RowVector3d::Zero();
  for (int v : m.src.sets.handle_vertices[0]) c0 += X.row(v);
  c0 /= static_cast<double>(m.src.sets.handle_vertices[0].size());
  const Eigen::Vector3d move = m.frame.s * (Q * (c0 - m.src.centroids.row(0)).transpose());
  Eigen::MatrixXd fixed(m.pins.size(), 3);
  for (size_t k = 0; k < m.pins.size(); ++k) fixed.row(k) = m.target.V.row(m.pins[k]) + move.transpose();
  Vertices out = m.eq12.solve({target_edges}, fixed);
  fit = 0, ref = 0;
  for (size_t e = 0; e < m.tgt.edges.size(); ++e) {
    const Eigen::RowVector3d d = out.row(m.tgt.edges[e][1]) - out.row(m.tgt.edges[e][0]);
    fit += (d - target_edges.row(e)).squaredNorm(), ref += target_edges.row(e).squaredNorm();
  }
  report_.eq12_residual = ref > 0 ? std::sqrt(fit / ref) : 0;
  return out;
}

}  // namespace lapis::mesh_deform
