#include "lapis/mesh_deform/implicit_laplacian.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <future>
#include <optional>

#include "implicit_rest.h"
#include "lapis/geometry/polar.h"
#include "lapis/solver/blas_threads.h"
#include "lapis/solver/least_squares.h"
#include "rotation_fit.h"
#include "rotation_guide.h"
#include "sparse_rows.h"
#include "stencil.h"

namespace lapis::mesh_deform {

using detail::SparseRows;

namespace {

// The metric of E_R: the Laplacian of the pair graph (degree on the diagonal, −1 per pair)
// over `slots` vertices, ⊗ I₃ (rows 3s + a, a = x y z). Written column by column: the same
// matrix from ~1M pairs as setFromTriplets on their 12 triplets each took 2–3× longer, most of
// it allocating and sorting the 12M triplets. Each pair appears once.
solver::SparseMatrix pair_graph_laplacian(int slots, const std::vector<std::pair<int, int>>& pairs) {
  std::vector<int> start(static_cast<size_t>(slots) + 1, 0);
  for (const auto& [a, b] : pairs) ++start[a + 1], ++start[b + 1];
  for (int v = 0; v < slots; ++v) start[v + 1] += start[v];
  std::vector<int> adjacent(static_cast<size_t>(start[slots]));
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (const auto& [a, b] : pairs) adjacent[fill[a]++] = b, adjacent[fill[b]++] = a;
  const std::ptrdiff_t entries = 3 * (static_cast<std::ptrdiff_t>(start[slots]) + slots);
  solver::SparseMatrix M(3 * slots, 3 * slots);
  M.resizeNonZeros(entries);
  int* outer = M.outerIndexPtr();
  int* inner = M.innerIndexPtr();
  double* value = M.valuePtr();
  std::ptrdiff_t at = 0;
  for (int v = 0; v < slots; ++v) {
    int* first = adjacent.data() + start[v];
    int* last = adjacent.data() + start[v + 1];
    std::sort(first, last);
    const int* diagonal = std::lower_bound(first, last, v);
    const double degree = static_cast<double>(last - first);
    for (int a = 0; a < 3; ++a) {
      outer[3 * v + a] = static_cast<int>(at);
      for (const int* u = first; u != last; ++u) {
        if (u == diagonal) inner[at] = 3 * v + a, value[at++] = degree;
        inner[at] = 3 * *u + a, value[at++] = -1.0;
      }
      if (diagonal == last) inner[at] = 3 * v + a, value[at++] = degree;
    }
  }
  outer[3 * slots] = static_cast<int>(at);
  return M;
}

// The mesh's edges as an n by n pattern: the skeleton on which Eq. 2.8's normal matrix is
// ordered (solver/ordering.h). Its columns couple vertices four rings apart, and METIS on
// that graph took a quarter of a one-off merge; the mesh's separators, widened, do nearly as
// well in a third of the time.
solver::SparseMatrix edge_graph(const detail::Stencil& s) {
  const int n = s.size();
  solver::SparseMatrix E(n, n);
  E.resizeNonZeros(static_cast<Eigen::Index>(s.nbr.size()));
  std::copy(s.offsets.begin(), s.offsets.end(), E.outerIndexPtr());
  std::copy(s.nbr.begin(), s.nbr.end(), E.innerIndexPtr());  // ascending per vertex, as stencils are
  std::fill(E.valuePtr(), E.valuePtr() + E.nonZeros(), 1.0);
  return E;
}

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
  std::vector<int> guide_rows;                     // vertex of each guide constraint
  solver::DenseMatrix guide_weights;               // φ_k at each guide vertex (rows) per handle
  solver::DenseMatrix guide_rest;                  // M_c(v') of the guide rows
  solver::DenseMatrix transform_rest;           // M_c(v') of the transformation-constraint rows
  solver::DenseMatrix blend_rest;               // E_T rows (§3.3.3) at the rest state
  solver::DenseMatrix delta;                    // D V at the free vertices (Eq. 2.10 rows)
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
  FirstSystemInput first_input(const HandleTransforms& transforms) const {
    const Vertices& P = w.displaced;
    FirstSystemInput in;
    in.fixed.resize(static_cast<Eigen::Index>(constrained.size()), 3);
    for (size_t k = 0; k < constrained.size(); ++k) {
      const int v = constrained[k];
      in.fixed.row(static_cast<Eigen::Index>(k)) = (place(transforms, v, P.row(v).transpose()) - P.row(v).transpose()).transpose();
    }
    // E_L and E_R vanish at the rest state (M_i = I), so their right-hand sides are zero
    // (empty: the solver skips them); only the transformation constraints carry W_c − M_c(v').
    in.rhs.resize(1);
    if (has_coherence) in.rhs.emplace_back();
    if (transform_rest.rows() > 0) {
      solver::DenseMatrix r = -transform_rest;
      for (size_t t = 0; t < transform_vertex.size(); ++t) {
        const int h = transform_handle[t];
        const Eigen::Matrix3d W = h < 0 ? Eigen::Matrix3d::Identity() : Eigen::Matrix3d(transforms.regions[h].topLeftCorner<3, 3>());
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
    for (int p = 0; p < point_handles; ++p) C.row(4 * region_handles + p) = transforms.points[static_cast<size_t>(p)].transpose();
    return C;
  }
};


ImplicitLaplacianDeformer::ImplicitLaplacianDeformer(TriMesh mesh, ImplicitOptions options)
    : Deformer(std::move(mesh)), options_(options) {}

ImplicitLaplacianDeformer::~ImplicitLaplacianDeformer() = default;

void ImplicitLaplacianDeformer::set_options(const ImplicitOptions& options) {
  constexpr const char* fn = "mesh_deform::ImplicitLaplacianDeformer::set_options()";
  if (!(options.degenerate_condition > 1)) throw InvalidArgument(std::string(fn) + ": degenerate_condition must be > 1");
  if (!(options.s_disp > 0) || !(options.coherence_weight > 0) || !(options.transform_weight > 0))
    throw InvalidArgument(std::string(fn) + ": s_disp, coherence_weight and transform_weight must be > 0");
  options_ = options;
  mark_dirty();
}

void ImplicitLaplacianDeformer::set_laplacian_blends(std::vector<LaplacianBlend> blends, double weight) {
  constexpr const char* fn = "mesh_deform::ImplicitLaplacianDeformer::set_laplacian_blends()";
  if (!(weight > 0) || !std::isfinite(weight)) throw InvalidArgument(std::string(fn) + ": weight must be finite and > 0");
  const int n = mesh_.num_vertices();
  auto in_range = [n](int v) { return v >= 0 && v < n; };
  for (const LaplacianBlend& b : blends) {
    bool ok = in_range(b.vertex);
    for (int k = 0; k < 3; ++k) ok = ok && in_range(b.others[k]) && std::isfinite(b.weights[k]);
    if (!ok) throw InvalidArgument(std::string(fn) + ": term at vertex " + std::to_string(b.vertex) +
                                   " has a vertex out of range or a weight that is not finite");
  }
  blends_ = std::move(blends);
  blend_weight_ = weight;
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
  const int n = w.mesh.num_vertices();
  const Vertices& P = w.displaced;
  for (int v = 0; v < n; ++v) (w.role[v] == VertexRole::Free ? m->free : m->constrained).push_back(v);
  m->polar_start.assign(m->free.size(), Eigen::Quaterniond::Identity());

  // Eq. 2.10/2.11's system is built and factorized on a second thread while Eq. 2.8's is built,
  // ordered and factorized on this one: started before E_L and E_R are assembled, it is done
  // before the first factorization is, and the first system's ordering (nested dissection,
  // CAMD) runs on one core and would leave the other idle.
  std::future<void> second_done;
  // Two factorizations at once: one BLAS thread each (blas_threads.h), else OpenBLAS' idle
  // threads busy-wait on the cores the other factorization needs.
  std::optional<solver::ScopedBlasThreads> one_blas_thread;
  if (options_.shearing != ShearingRemoval::None) {
    one_blas_thread.emplace(1);
    // It reads w, free and constrained, which this thread only reads, and writes only
    // m->second and m->delta, which this thread reads after joining. On an exception below,
    // second_done's destructor joins before m is destroyed.
    second_done = std::async(std::launch::async, [&m = *m, &w, n, weights = options_.weights] {
      // Eq. 2.10/2.11 on the undisplaced mesh: the rotations carry the deformation, the rest
      // Laplacian the details.
      detail::Stencil s0 = w.stencil;
      detail::reweight(s0, w.mesh.V, w.mesh.F, weights);
      SparseRows D(n);
      for (int i : m.free) detail::add_laplacian_row(D, s0, i);
      m.second = solver::LeastSquares(n);
      m.second.add_block(D.matrix(), 1.0, "D(v) = R S δ (Eq. 2.10/2.11)");  // taken, not copied
      m.second.set_fixed(m.constrained);
      m.delta = m.second.block_matrix(0) * solver::DenseMatrix(w.mesh.V);
      m.second.precompute();
    });
  }

  // §2.4.3: the Laplacian of the displaced mesh, so a displaced vertex's δ points along its
  // normal (cotangent weights; uniform ones add the tangential part of Fig. 2.5).
  detail::Stencil s = w.stencil;
  detail::reweight(s, P, w.mesh.F, options_.weights);
  const Vertices deltaP = detail::laplacian_coordinates(s, P);
  m->G = detail::gradient_stencils(s, P, w.active);
  const detail::GradientStencils& G = m->G;
  const double h = detail::mean_edge_length(s, w.mesh.V);

  // Does M_i depend on a free unknown? Terms that do not are constants and left out.
  std::vector<char> touches(static_cast<size_t>(n), 0);
  for (int i = 0; i < n; ++i)
    for (int k = G.offsets[i]; k < G.offsets[i + 1]; ++k)
      if (w.role[G.vertex[k]] == VertexRole::Free) touches[i] = 1;

  // E_L (Eq. 2.6): D(ṽ_i) − M_i δ_i, one row per free vertex and coordinate.
  SparseRows EL(n);
  for (int i : m->free) {
    detail::add_laplacian_row(EL, s, i);
    for (int k = G.offsets[i]; k < G.offsets[i + 1]; ++k) EL.add(G.vertex[k], -G.g[k].dot(deltaP.row(i)));
  }
  // E_R (Eq. 2.7): Σ ‖M_i − M_j‖² over pairs within 2 rings (footnote 1). M_i's rows are
  // linear in the positions (the gradient stencil g_i), so E_R = Σ_a xᵀ G_aᵀ (Dᵀ D) G_a x with
  // D the pairs' incidence matrix: three rows g_i(a) per vertex in a pair, measured in the
  // metric Dᵀ D ⊗ I₃ (the pair graph's Laplacian), rather than three rows g_i(a) − g_j(a) per
  // pair — the same energy from a normal matrix that costs several times less to assemble.
  SparseRows ER(n);
  std::vector<int> slot(static_cast<size_t>(n), -1);  // vertex → its three rows / 3
  std::vector<std::pair<int, int>> pairs;              // slots of the vertices of each pair
  auto slot_of = [&](int i) {
    if (slot[i] < 0) {
      slot[i] = ER.rows() / 3;
      for (int a = 0; a < 3; ++a) {
        ER.begin_row();
        for (int k = G.offsets[i]; k < G.offsets[i + 1]; ++k) ER.add(G.vertex[k], G.g[k](a));
      }
    }
    return slot[i];
  };
  std::vector<int> stamp(static_cast<size_t>(n), -1);
  for (int i = 0; i < n; ++i) {
    if (!w.active[i]) continue;
    stamp[i] = i;
    auto visit = [&](int j) {
      if (stamp[j] == i) return;
      stamp[j] = i;
      if (j < i || !w.active[j] || !(touches[i] || touches[j])) return;
      const int si = slot_of(i);
      pairs.emplace_back(si, slot_of(j));
    };
    for (int k = s.offsets[i]; k < s.offsets[i + 1]; ++k) {
      const int j = s.nbr[k];
      visit(j);
      for (int l = s.offsets[j]; l < s.offsets[j + 1]; ++l) visit(s.nbr[l]);
    }
  }
  // Eq. 2.8 transformation constraints: region handles carry their transform's linear part,
  // the border of the fixed region the identity. Point handles constrain positions only.
  SparseRows T(n);
  for (int c : m->constrained) {
    if (!w.active[c] || !touches[c] || w.role[c] == VertexRole::PointHandle) continue;
    m->transform_vertex.push_back(c);
    m->transform_handle.push_back(w.role[c] == VertexRole::RegionHandle ? w.handle_of[c] : -1);
    for (int a = 0; a < 3; ++a) {
      T.begin_row();
      for (int k = G.offsets[c]; k < G.offsets[c + 1]; ++k) T.add(G.vertex[k], G.g[k](a));
    }
  }

  // E_T (§3.3.3): row M_i δ_i − Σ_j b_j M_j δ_j, linear in the unknowns like E_L's M_i δ_i.
  SparseRows EB(n);
  auto add_transformed = [&](int i, double b) {
    for (int k = G.offsets[i]; k < G.offsets[i + 1]; ++k) EB.add(G.vertex[k], b * G.g[k].dot(deltaP.row(i)));
  };
  for (const LaplacianBlend& t : blends_) {
    bool defined = G.offsets[t.vertex] < G.offsets[t.vertex + 1], free = touches[t.vertex];
    for (int j : t.others) defined = defined && G.offsets[j] < G.offsets[j + 1], free = free || touches[j];
    if (!defined || !free) continue;
    EB.begin_row();
    add_transformed(t.vertex, 1.0);
    for (int k = 0; k < 3; ++k)
      if (t.weights[k] != 0) add_transformed(t.others[k], -t.weights[k]);
  }

  m->first = solver::LeastSquares(n);
  m->weight_R = options_.coherence_weight * h * h;
  m->weight_T = options_.transform_weight * h * h;
  // Each block goes to the solver as the builder's temporary, taken without a copy (tens of
  // MB at 50K vertices, each page of a copy faulted in afresh).
  m->first.add_block(EL.matrix(), 1.0, "E_L (Eq. 2.6)");
  if (ER.rows() > 0)
    m->block_R = m->first.add_block(ER.matrix(), m->weight_R, "E_R (Eq. 2.7)", pair_graph_laplacian(ER.rows() / 3, pairs));
  if (T.rows() > 0) m->block_T = m->first.add_block(T.matrix(), m->weight_T, "M_c = W_c (Eq. 2.8)");
  if (EB.rows() > 0) m->block_B = m->first.add_block(EB.matrix(), blend_weight_, "E_T (§3.3.3)");
  m->first.set_fixed(m->constrained);
  m->first.set_ordering_skeleton(edge_graph(s));
  m->stencil = s;
  m->accumulated.assign(static_cast<size_t>(layout.num_region_handles), Eigen::Vector3d::Zero());
  m->has_coherence = m->block_R >= 0;
  // M_c(v') and E_T's rows at the rest state; no rows when the block is absent.
  const auto at_rest = [&](int block) {
    return block >= 0 ? solver::DenseMatrix(m->first.block_matrix(block) * solver::DenseMatrix(P)) : solver::DenseMatrix(0, 3);
  };
  m->transform_rest = at_rest(m->block_T);
  m->blend_rest = at_rest(m->block_B);

  try {
    m->first.precompute();
  } catch (...) {
    if (second_done.valid()) second_done.wait();  // the first system's error is the one to report
    throw;
  }
  if (second_done.valid()) second_done.get();  // rethrows the second system's error
  m->region_handles = layout.num_region_handles;
  m->point_handles = layout.num_point_handles;
  const int parameters = 4 * m->region_handles + m->point_handles;
  if (parameters <= options_.max_basis_columns) m->build_basis();

  stats_ = {};
  stats_.free_vertices = static_cast<int>(m->free.size());
  stats_.degenerate_vertices = w.degenerate;
  stats_.inserted_vertices = static_cast<int>(w.inserted.size());
  stats_.first_factor_nnz = m->first.factor().stats().nnz_L;
  stats_.basis_columns = static_cast<int>(m->basis.cols());
  if (options_.shearing != ShearingRemoval::None) stats_.second_factor_nnz = m->second.factor().stats().nnz_L;
  impl_ = std::move(m);
  stats_.setup_ms = ms_since(t0);
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
  for (size_t t = 0; t < m.guide_rows.size(); ++t) m.guide_weights.row(static_cast<Eigen::Index>(t)) = fields.row(m.guide_rows[t]);
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
  m.guided->add_block(A_G, m.weight_T, "guide bands (§2.5)");
  m.guided->set_fixed(m.constrained);
  m.guided->set_ordering_skeleton(edge_graph(m.stencil));
  m.guided->precompute();
  m.guide_rest = A_G * solver::DenseMatrix(w.displaced);
  m.guided_for = handles;
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
  stats_.guided = !big.empty();
  solver::DenseMatrix X;
  if (big.empty() && m.basis.cols() > 0) {
    X = solver::DenseMatrix(P) + m.at_identity;
    X.noalias() += m.basis * m.basis_coefficients(transforms);
  } else if (big.empty()) {
    const FirstSystemInput in = m.first_input(transforms);
    X = solver::DenseMatrix(P) + m.first.solve(in.rhs, in.fixed);
  } else {
    FirstSystemInput in = m.first_input(transforms);
    if (big != m.guided_for) build_guide(big);
    solver::DenseMatrix g = -m.guide_rest;
    // Each guide vertex takes the φ-blend of the handles' accumulated rotation vectors and
    // log-scales (the fixed region contributes the identity with weight 1 − Σ φ_k).
    std::vector<double> log_scale(m.accumulated.size());
    for (size_t h = 0; h < m.accumulated.size(); ++h)
      log_scale[h] = std::log(std::cbrt(std::abs(transforms.regions[h].topLeftCorner<3, 3>().determinant())));
    for (size_t t = 0; t < m.guide_rows.size(); ++t) {
      Eigen::Vector3d r = Eigen::Vector3d::Zero();
      double ls = 0;
      for (size_t h = 0; h < m.accumulated.size(); ++h) {
        const double phi = m.guide_weights(static_cast<Eigen::Index>(t), static_cast<Eigen::Index>(h));
        r += phi * m.accumulated[h];
        ls += phi * log_scale[h];
      }
      g.middleRows(static_cast<Eigen::Index>(3 * t), 3) += (std::exp(ls) * detail::rotation_of(r)).transpose();
    }
    in.rhs.push_back(std::move(g));
    X = solver::DenseMatrix(P) + m.guided->solve(in.rhs, in.fixed);
  }
  stats_.first_solve_ms = ms_since(t0);

  if (options_.shearing == ShearingRemoval::None || preview_) {
    // Pull-back of displaced vertices (§2.4.3): ṽ_i = M_i (v_i − v'_i) + ṽ'_i.
    const Vertices Xv = X;
    for (int v : m.free)
      if (v < n0) out.row(v) = Xv.row(v);
    for (int v : w.moved)
      if (v < n0 && w.role[v] == VertexRole::Free)
        out.row(v) = Xv.row(v) + (m.G.gradient(v, Xv) * (w.mesh.V.row(v) - P.row(v)).transpose()).transpose();
    for (int v : m.constrained)
      if (v < n0) out.row(v) = targets.row(v);
    stats_.polar_ms = stats_.second_solve_ms = 0;
    stats_.frame_ms = ms_since(t_frame);
    return;
  }

  // Shearing removal (§2.4.4): M_i = R_i S_i, s_i = sqrt((λ1² + λ2² + λ3²) / 3) = ‖M_i‖_F / √3.
  t0 = std::chrono::steady_clock::now();
  const Vertices Xv = X;
  const int nf = static_cast<int>(m.free.size());
  solver::DenseMatrix rhs2(nf, 3);
  const bool scale = options_.shearing == ShearingRemoval::ScaleFeatures;
  int fallbacks = 0;
#pragma omp parallel for schedule(dynamic, detail::kVertexChunk) reduction(+ : fallbacks)
  for (int k = 0; k < nf; ++k) {
    const int v = m.free[k];
    const Eigen::Matrix3d M = m.G.gradient(v, Xv);
    bool fell_back = false;
    // Frames of a drag differ little: last frame's rotation starts the fit (rotation_fit.h).
    const Eigen::Matrix3d R = detail::nearest_rotation(M, m.polar_start[k], &fell_back);
    fallbacks += fell_back;
    const double s_i = scale ? M.norm() / std::sqrt(3.0) : 1.0;
    const Eigen::Vector3d d = m.delta.row(k).transpose();
    rhs2.row(k) = (s_i * (R * d) - d).transpose();
  }
  stats_.polar_fallbacks = fallbacks;
  stats_.polar_ms = ms_since(t0);

  t0 = std::chrono::steady_clock::now();
  solver::DenseMatrix fixed2(m.constrained.size(), 3);
  for (size_t k = 0; k < m.constrained.size(); ++k) {
    const int v = m.constrained[k];
    const Eigen::Vector3d r = w.mesh.V.row(v).transpose();
    fixed2.row(k) = (m.place(transforms, v, r) - r).transpose();
  }
  const solver::DenseMatrix Y = m.second.solve({rhs2}, fixed2);
  for (int v : m.free)
    if (v < n0) out.row(v) = w.mesh.V.row(v) + Y.row(v);
  stats_.second_solve_ms = ms_since(t0);
  stats_.frame_ms = ms_since(t_frame);
}

}  // namespace lapis::mesh_deform
