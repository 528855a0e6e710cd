#include "lapis/mesh_deform/naive_laplacian.h"

#include <cmath>

#include "lapis/solver/least_squares.h"
#include "sparse_rows.h"
#include "stencil.h"

namespace lapis::mesh_deform {

// Solved for displacements from the rest mesh: Eq. 2.1's right-hand side δ_i − D(v_i) is then
// exactly zero and only the handles drive the solution.
struct NaiveLaplacianDeformer::Impl {
  solver::LeastSquares ls{1};
  std::vector<int> fixed;  // eliminated: outside the ROI (+ handles when hard)
  std::vector<int> soft;   // soft handle vertices, one position row each
  int rows_laplacian = 0;
};

NaiveLaplacianDeformer::NaiveLaplacianDeformer(TriMesh mesh, NaiveOptions options)
    : Deformer(std::move(mesh)), options_(options) {}
NaiveLaplacianDeformer::~NaiveLaplacianDeformer() = default;

void NaiveLaplacianDeformer::set_options(const NaiveOptions& options) {
  if (!(options.handle_weight > 0) || !std::isfinite(options.handle_weight))
    throw InvalidArgument("mesh_deform::NaiveLaplacianDeformer::set_options(): handle_weight must be finite and > 0");
  options_ = options;
  mark_dirty();
}

void NaiveLaplacianDeformer::setup(const Layout& layout) {
  auto m = std::make_unique<Impl>();
  const int n = mesh_.num_vertices();
  const detail::Stencil s = detail::make_stencil(mesh_.V, mesh_.F, options_.weights);
  detail::SparseRows D(n), H(n);
  for (int i = 0; i < n; ++i) {
    const VertexRole r = layout.role[i];
    const bool unknown = r == VertexRole::Free || (options_.soft_handles && r != VertexRole::Fixed);
    if (!unknown) {
      m->fixed.push_back(i);
      continue;
    }
    detail::add_laplacian_row(D, s, i);
    if (r != VertexRole::Free) {
      m->soft.push_back(i);
      H.begin_row();
      H.add(i, 1.0);
    }
  }
  m->ls = solver::LeastSquares(n);
  m->ls.add_block(D.matrix(), 1.0, "D(v) = δ (Eq. 2.1)");
  if (!m->soft.empty()) m->ls.add_block(H.matrix(), options_.handle_weight, "soft handles");
  m->ls.set_fixed(m->fixed);
  m->ls.precompute();
  m->rows_laplacian = D.rows();
  impl_ = std::move(m);
}

void NaiveLaplacianDeformer::solve(const HandleTransforms&, const Vertices& targets, Vertices& out) {
  const Impl& m = *impl_;
  solver::DenseMatrix fixed(m.fixed.size(), 3);
  for (size_t k = 0; k < m.fixed.size(); ++k) fixed.row(k) = targets.row(m.fixed[k]) - mesh_.V.row(m.fixed[k]);
  std::vector<solver::DenseMatrix> rhs{solver::DenseMatrix::Zero(m.rows_laplacian, 3)};
  if (!m.soft.empty()) {
    solver::DenseMatrix r(m.soft.size(), 3);
    for (size_t k = 0; k < m.soft.size(); ++k) r.row(k) = targets.row(m.soft[k]) - mesh_.V.row(m.soft[k]);
    rhs.push_back(std::move(r));
  }
  const solver::DenseMatrix d = m.ls.solve(rhs, fixed);
  out = mesh_.V + Vertices(d);
}

}  // namespace lapis::mesh_deform
