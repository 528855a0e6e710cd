#include "multigrid_hierarchy.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <unordered_map>

#include "lapis/core/error.h"
#include "grid_stencil.h"
#include "grid_transfer.h"
#include "lapis/hair_field/grid_operators.h"

namespace lapis::hair_field::detail {
namespace {

// 1D interpolation weights of fine node f from the coarse nodes at f/2 (every other fine
// node is a coarse node; odd ones average their two coarse neighbours). Optionally cubic
// (−1, 9, 9, −1)/16 where four coarse neighbours exist, as textbook multigrid for a
// 4th-order operator suggests (orders of prolongation + restriction > 4); measured on the
// field system it converged worse (70 vs 41 CG iterations at 33³), so linear is the default.
inline int weights_1d(int f, int nc, bool cubic, std::array<std::pair<int, double>, 4>& w) {
  if (f % 2 == 0) {
    w[0] = {f / 2, 1.0};
    return 1;
  }
  const int a = (f - 1) / 2;
  if (cubic && a - 1 >= 0 && a + 2 < nc) {
    w[0] = {a - 1, -1.0 / 16};
    w[1] = {a, 9.0 / 16};
    w[2] = {a + 1, 9.0 / 16};
    w[3] = {a + 2, -1.0 / 16};
    return 4;
  }
  w[0] = {a, 0.5};
  w[1] = {a + 1, 0.5};
  return 2;
}

RowSparseD prolongation(const std::array<int, 3>& fd, const std::array<int, 3>& cd, bool cubic) {
  const int nf = fd[0] * fd[1] * fd[2], nc = cd[0] * cd[1] * cd[2];
  std::vector<Eigen::Triplet<double, int>> t;
  t.reserve(static_cast<size_t>(nf) * 4);
  std::array<std::pair<int, double>, 4> wx, wy, wz;
  for (int k = 0; k < fd[2]; ++k) {
    const int nzw = weights_1d(k, cd[2], cubic, wz);
    for (int j = 0; j < fd[1]; ++j) {
      const int nyw = weights_1d(j, cd[1], cubic, wy);
      for (int i = 0; i < fd[0]; ++i) {
        const int nxw = weights_1d(i, cd[0], cubic, wx);
        const int row = i + fd[0] * (j + fd[1] * k);
        for (int c = 0; c < nzw; ++c)
          for (int b = 0; b < nyw; ++b)
            for (int a = 0; a < nxw; ++a)
              t.emplace_back(row, wx[a].first + cd[0] * (wy[b].first + cd[1] * wz[c].first),
                             wx[a].second * wy[b].second * wz[c].second);
      }
    }
  }
  RowSparseD P(nf, nc);
  P.setFromTriplets(t.begin(), t.end());
  return P;
}

// Position of entry (i, j) in A's value array, or -1 if it is not in the pattern.
inline std::ptrdiff_t value_index(const RowSparseD& A, int i, int j) {
  const int* begin = A.innerIndexPtr() + A.outerIndexPtr()[i];
  const int* end = A.innerIndexPtr() + A.outerIndexPtr()[i + 1];
  const int* it = std::lower_bound(begin, end, j);
  return (it != end && *it == j) ? it - A.innerIndexPtr() : -1;
}

enum class Mode { Assign, Add, Subtract };

// Below this many stored entries a sparse product runs on one thread. The threshold counts
// entries, not rows: level 1 of a 50K grid has only 7.4K rows but 0.9M entries (up to 125
// a row), the costliest product of the cycle, and a row threshold left it on one thread.
constexpr std::ptrdiff_t parallel_nonzeros = 50000;
// Element-wise passes: below this many nodes one thread.
constexpr int parallel_nodes = 20000;

// y = A x, y += A x or y -= A x, 3 columns at once.
void spmv(const RowSparseF& A, const FieldF& x, FieldF& y, Mode mode) {
  const int n = static_cast<int>(A.rows());
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  const Real* val = A.valuePtr();
  const Real* xp = x.data();
  Real* yp = y.data();
#pragma omp parallel for schedule(static) if (A.nonZeros() > parallel_nonzeros)
  for (int i = 0; i < n; ++i) {
    Real s0 = 0, s1 = 0, s2 = 0;
    for (int p = outer[i]; p < outer[i + 1]; ++p) {
      const Real v = val[p];
      const Real* xc = xp + 3 * static_cast<std::ptrdiff_t>(inner[p]);
      s0 += v * xc[0];
      s1 += v * xc[1];
      s2 += v * xc[2];
    }
    Real* yi = yp + 3 * static_cast<std::ptrdiff_t>(i);
    if (mode == Mode::Subtract) {
      yi[0] -= s0, yi[1] -= s1, yi[2] -= s2;
    } else if (mode == Mode::Add) {
      yi[0] += s0, yi[1] += s1, yi[2] += s2;
    } else {
      yi[0] = s0, yi[1] = s1, yi[2] = s2;
    }
  }
}

// Four floats as one SSE register (GCC/Clang vector extension): the compiler did not
// vectorize the 3-column gather loop by itself.
typedef Real Real4 __attribute__((vector_size(4 * sizeof(Real))));

inline Real4 load4(const Real* p) {
  Real4 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

// s[0..2] = (A u)_i, 3 columns. A row has up to 125 entries. Where the row's last column
// is not the vector's last node, an entry's 3 values are read as 4 (the 4th belongs to the
// next node and is ignored) and multiplied and added as one vector, in two partial sums so
// consecutive entries do not wait for each other's addition.
inline void row_product(const RowSparseF& A, const Real* u, int i, Real s[4]) {
  const int* inner = A.innerIndexPtr();
  const Real* val = A.valuePtr();
  const int begin = A.outerIndexPtr()[i], end = A.outerIndexPtr()[i + 1];
  Real4 a0 = {0, 0, 0, 0}, a1 = {0, 0, 0, 0};
  int p = begin;
  if (end > begin && inner[end - 1] + 1 < A.cols()) {
    for (; p + 2 <= end; p += 2) {
      a0 += val[p] * load4(u + 3 * static_cast<std::ptrdiff_t>(inner[p]));
      a1 += val[p + 1] * load4(u + 3 * static_cast<std::ptrdiff_t>(inner[p + 1]));
    }
  }
  a0 += a1;
  for (int k = 0; k < 4; ++k) s[k] = a0[k];
  for (; p < end; ++p) {
    const Real v = val[p];
    const Real* uc = u + 3 * static_cast<std::ptrdiff_t>(inner[p]);
    for (int k = 0; k < 3; ++k) s[k] += v * uc[k];
  }
}

// y += x.
void add(const FieldF& x, FieldF& y) {
  const std::ptrdiff_t size = x.size();
  const Real* xp = x.data();
  Real* yp = y.data();
#pragma omp parallel for schedule(static) if (size > 3 * parallel_nodes)
  for (std::ptrdiff_t f = 0; f < size; ++f) yp[f] += xp[f];
}

// r = b − A x on a sparse level.
void sparse_residual(const RowSparseF& A, const Real* x, const Real* b, Real* r) {
  const int n = static_cast<int>(A.rows());
#pragma omp parallel for schedule(static) if (A.nonZeros() > parallel_nonzeros)
  for (int i = 0; i < n; ++i) {
    Real s[4];
    row_product(A, x, i, s);
    for (std::ptrdiff_t k = 0; k < 3; ++k) r[3 * i + k] = b[3 * i + k] - s[k];
  }
}

// One Chebyshev step on a sparse level fused with the product before it, in one pass:
//   r_out = r_in − A u,  d_new = a d + c D⁻¹ r_out,  x += d_new (+ d when add_d).
// u is d, except in the first step of a smoothing from a non-zero x, where u is x itself:
// that step may not write x while other rows still gather from it, so it passes
// x = nullptr and the next step adds both corrections (add_d). d_new is a separate buffer
// for the same reason. d may be nullptr when a = 0.
void sparse_chebyshev_step(const RowSparseF& A, const Real* u, const Real* d, Real* d_new,
                           Real* x, bool add_d, const Real* r_in, Real* r_out,
                           const VectorR& inv_diag, Real a, Real c) {
  const int n = static_cast<int>(A.rows());
#pragma omp parallel for schedule(static) if (A.nonZeros() > parallel_nonzeros)
  for (int i = 0; i < n; ++i) {
    Real s[4];
    row_product(A, u, i, s);
    const Real ci = c * inv_diag[i];
    for (int k = 0; k < 3; ++k) {
      const std::ptrdiff_t f = 3 * static_cast<std::ptrdiff_t>(i) + k;
      const Real r = r_in[f] - s[k];
      r_out[f] = r;
      const Real dn = (d ? a * d[f] : Real(0)) + ci * r;
      d_new[f] = dn;
      if (x) x[f] += add_d ? dn + d[f] : dn;
    }
  }
}

}  // namespace

MultigridHierarchy::MultigridHierarchy(const Grid& grid, const Eigen::VectorXd& weights,
                                       MultigridOptions options)
    : opt_(options) {
  opt_.smoothing_degree = std::max(1, opt_.smoothing_degree);
  opt_.cycle_index = std::max(1, opt_.cycle_index);
  // The hierarchy of the unconstrained operator DᵀD first; the weights then arrive as an
  // edit, exactly as later constraint changes do.
  Level fine;
  fine.dims = grid.dims;
  fine.A = RowSparseD(normal_matrix(grid, Eigen::VectorXd::Zero(grid.num_nodes())));
  levels_.push_back(std::move(fine));
  while (levels_.back().A.rows() > opt_.coarsest_nodes) {
    Level& f = levels_.back();
    const std::array<int, 3> cd{f.dims[0] / 2 + 1, f.dims[1] / 2 + 1, f.dims[2] / 2 + 1};
    if (cd == f.dims) break;  // cannot coarsen further (2 nodes per axis)
    f.Pd = prolongation(f.dims, cd, opt_.cubic);
    Level c;
    c.dims = cd;
    const RowSparseD AP = f.A * f.Pd;
    c.A = RowSparseD(f.Pd.transpose()) * AP;
    c.A.makeCompressed();
    // The finest level's linear transfers are applied matrix-free (grid_transfer.h).
    if (levels_.size() > 1 || opt_.cubic) {
      f.P = f.Pd.cast<Real>();
      f.R = RowSparseF(f.P.transpose());
    }
    levels_.push_back(std::move(c));
  }
  // Corrections per visit of each level: one on the finest unless asked otherwise, one where
  // the next level is the coarsest (its solve is exact), else coarse_cycle_index.
  // Automatic: more corrections pay once the hierarchy is deep enough for the V-cycle's
  // weakening with depth to cost iterations (multigrid_field_solver.h has the figures), but
  // at most two into a level small enough for its products to run on one thread: there the
  // other thread waits, so each correction costs twice its share, and the visits multiply
  // down the tree (250K: 12 and 13 iterations after a stroke and an edit either way, the
  // level 3 below it visited 8 times a cycle instead of 16).
  const bool automatic = opt_.coarse_cycle_index <= 0;
  if (automatic) opt_.coarse_cycle_index = levels_.size() >= 5 ? 4 : 2;
  corrections_.assign(levels_.size(), 1);
  for (size_t l = 0; l + 2 < levels_.size(); ++l) {
    const bool serial = levels_[l + 1].A.nonZeros() <= parallel_nonzeros;
    corrections_[l] = l == 0 ? opt_.cycle_index
                      : automatic && serial ? std::min(2, opt_.coarse_cycle_index)
                                            : opt_.coarse_cycle_index;
  }
  Level& f0 = levels_[0];
  f0.matrix_free = true;
  f0.weights.setZero(f0.A.rows());
  fine_weights_.setZero(f0.A.rows());
  pinned_.assign(f0.A.rows(), 0);
  for (Level& L : levels_) {
    const int n = static_cast<int>(L.A.rows());
    if (!L.matrix_free) L.Af = L.A.cast<Real>();
    L.inv_diag.resize(n);
    if (L.matrix_free) L.inv_diag3.resize(3 * n);
    L.gershgorin.resize(n);
    for (int i = 0; i < n; ++i) refresh_row(L, i);
    L.lambda_max = L.gershgorin.maxCoeff();
    L.x.setZero(n, 3);
    L.b.setZero(n, 3);
    L.r.setZero(n, 3);
    L.d.setZero(n, 3);
    if (!L.matrix_free) L.d2.setZero(n, 3);
    if (&L != &levels_.front()) L.b0.setZero(n, 3), L.e.setZero(n, 3);
    L.base_diag = L.A.diagonal();
  }
  factor_coarsest();
  std::vector<std::pair<int, double>> initial;
  for (int i = 0; i < weights.size(); ++i)
    if (weights[i] != 0) initial.emplace_back(i, weights[i]);
  if (!initial.empty()) add_to_diagonal(initial);
}

void MultigridHierarchy::refresh_row(Level& L, int row) {
  double diag = 0, sum = 0;
  for (std::ptrdiff_t p = L.A.outerIndexPtr()[row]; p < L.A.outerIndexPtr()[row + 1]; ++p) {
    const double v = L.A.valuePtr()[p];
    if (!L.matrix_free) L.Af.valuePtr()[p] = static_cast<Real>(v);
    if (L.A.innerIndexPtr()[p] == row) diag = v;
    sum += std::abs(v);
  }
  // A zero diagonal only occurs for a coarse node outside the fine box that no fine node
  // interpolates from; such a node has an empty row and never receives a residual.
  L.inv_diag[row] = diag > 0 ? static_cast<Real>(1.0 / diag) : Real(0);
  if (L.matrix_free) L.inv_diag3.segment(3 * row, 3).setConstant(L.inv_diag[row]);
  L.gershgorin[row] = diag > 0 ? static_cast<Real>(sum / diag) : Real(0);
}

void MultigridHierarchy::factor_coarsest() {
  coarsest_.compute(Eigen::MatrixXd(levels_.back().A));
}

void MultigridHierarchy::add_to_diagonal(const std::vector<std::pair<int, double>>& changes) {
  // The fine level takes the weights on its diagonal; the nodes whose pinned state flips
  // change level 1 through the prolongation (free_set_change); what level 1 gains or loses
  // spreads to the coarser levels entry by entry.
  Level& F = levels_[0];
  std::vector<Entry> T;
  T.reserve(changes.size());
  for (const auto& [node, delta] : changes) {
    T.push_back({node, node, delta});
    fine_weights_[node] += delta;
    F.weights[node] = static_cast<Real>(fine_weights_[node]);
  }
  update_level(0, T);
  std::unordered_map<long long, double> acc;
  for (const auto& [node, delta] : changes) {
    const bool pinned = fine_weights_[node] > 0;
    if (pinned == static_cast<bool>(pinned_[node])) continue;
    // (A single-level hierarchy has no prolongation: the dense solve is all of it.)
    if (levels_.size() > 1) free_set_change(node, pinned ? -1.0 : 1.0, acc);
    if (opt_.cubic && levels_.size() > 1) set_prolongation_row(node, !pinned);
    pinned_[node] = pinned;
  }
  for (size_t l = 1; l < levels_.size(); ++l) {
    T.clear();
    for (const auto& [key, v] : acc) {
      const long long nc = levels_[l].A.rows();
      T.push_back({static_cast<int>(key / nc), static_cast<int>(key % nc), v});
    }
    update_level(static_cast<int>(l), T);
    if (l + 1 == levels_.size()) break;
    // Pᵀ ΔA P, entry by entry: (i, j, v) spreads to (I, J, P(i,I) v P(j,J)).
    const Level& L = levels_[l];
    const long long nc = levels_[l + 1].A.rows();
    acc.clear();
    for (const Entry& e : T)
      for (RowSparseD::InnerIterator a(L.Pd, e.i); a; ++a)
        for (RowSparseD::InnerIterator b(L.Pd, e.j); b; ++b)
          acc[a.col() * nc + b.col()] += a.value() * e.v * b.value();
  }
  factor_coarsest();
}

void MultigridHierarchy::update_level(int l, const std::vector<Entry>& T) {
  Level& L = levels_[l];
  std::vector<int> rows;
  rows.reserve(T.size());
  for (const Entry& e : T) {
    const std::ptrdiff_t p = value_index(L.A, e.i, e.j);
    if (p < 0)
      throw SolverFailure("hair_field::MultigridHierarchy::add_to_diagonal(): entry (" +
                          std::to_string(e.i) + ", " + std::to_string(e.j) +
                          ") outside the Galerkin pattern of level " + std::to_string(l));
    L.A.valuePtr()[p] += e.v;
    rows.push_back(e.i);
  }
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  for (int r : rows) refresh_row(L, r);
  L.lambda_max = L.gershgorin.maxCoeff();
}

void MultigridHierarchy::free_set_change(int s, double sign,
                                         std::unordered_map<long long, double>& acc) const {
  // Level 1 is Σ_{i,j free} P_iᵀ A_ij P_j over the unweighted DᵀD (a pinned row of P is
  // zero). Node s joining (+) or leaving (−) the free set adds or removes the terms with
  // i = s or j = s, counted while s is free.
  const Level& F = levels_[0];
  const long long nc = levels_[1].A.rows();
  for (RowSparseD::InnerIterator a(F.A, s); a; ++a) {
    const int j = static_cast<int>(a.col());
    if (j != s && pinned_[j]) continue;
    const double v = j == s ? F.base_diag[s] : a.value();
    for (RowSparseD::InnerIterator ps(F.Pd, s); ps; ++ps)
      for (RowSparseD::InnerIterator pj(F.Pd, j); pj; ++pj) {
        const double t = sign * v * ps.value() * pj.value();
        acc[ps.col() * nc + pj.col()] += t;
        if (j != s) acc[pj.col() * nc + ps.col()] += t;
      }
  }
}

void MultigridHierarchy::set_prolongation_row(int s, bool free) {
  Level& F = levels_[0];
  for (std::ptrdiff_t p = F.P.outerIndexPtr()[s]; p < F.P.outerIndexPtr()[s + 1]; ++p) {
    const Real v = free ? static_cast<Real>(F.Pd.valuePtr()[p]) : Real(0);
    F.P.valuePtr()[p] = v;
    // The same entry of R = Pᵀ: row P.col, column s.
    const int c = F.P.innerIndexPtr()[p];
    const int* begin = F.R.innerIndexPtr() + F.R.outerIndexPtr()[c];
    const int* end = F.R.innerIndexPtr() + F.R.outerIndexPtr()[c + 1];
    F.R.valuePtr()[std::lower_bound(begin, end, s) - F.R.innerIndexPtr()] = v;
  }
}

void MultigridHierarchy::residual(Level& L) {
  const Real* b = L.b.data();
  Real* r = L.r.data();
  if (L.matrix_free) {
    // Zero at the pinned nodes: the residual only goes to the restriction, whose columns
    // there are zero (grid_transfer.h relies on it).
    const char* pinned = pinned_.data();
    normal_operator_visit(L.dims, L.weights.data(), L.x.data(), L.buffers,
                          [&](std::ptrdiff_t f0, std::ptrdiff_t len, const Real* v) {
                            for (std::ptrdiff_t f = 0; f < len; ++f) r[f0 + f] = b[f0 + f] - v[f];
                            const char* pin = pinned + f0 / 3;
                            for (std::ptrdiff_t i = 0; i < len / 3; ++i)
                              if (pin[i]) r[f0 + 3 * i] = r[f0 + 3 * i + 1] = r[f0 + 3 * i + 2] = 0;
                          });
  } else {
    sparse_residual(L.Af, L.x.data(), L.b.data(), L.r.data());
  }
}

void MultigridHierarchy::chebyshev_step(Level& L, bool from_x, bool& pending, const Real* r_in,
                                        Real a, Real c, bool last, bool post) {
  Real* r = L.r.data();
  if (L.matrix_free) {
    // The matrix-free apply's second pass reads its operand only on the line it visits, so
    // the step updates d (or x) in place, a line at a time. The last step of a smoothing
    // stores neither r nor d, which nothing reads before they are next written; the last
    // step of the cycle also forms the caller's dot products with z (apply()).
    Real* x = L.x.data();
    Real* d = L.d.data();
    const Real* inv = L.inv_diag3.data();
    const bool dot = last && post && dot_with_ != nullptr && &L == &levels_.front();
    if (dot) dot_done_ = true;
    normal_operator_visit(L.dims, L.weights.data(), from_x ? x : d, L.buffers,
                          [&](std::ptrdiff_t f0, std::ptrdiff_t len, const Real* v) {
                            Real* xl = x + f0;
                            Real* dl = d + f0;
                            Real* rl = r + f0;
                            const Real* rin = r_in + f0;
                            const Real* il = inv + f0;
                            if (last) {
                              const Real da = from_x ? Real(0) : a;
                              for (std::ptrdiff_t f = 0; f < len; ++f)
                                xl[f] += da * dl[f] + c * il[f] * (rin[f] - v[f]);
                              if (dot) {
                                const double* wl = dot_with_ + f0;
                                double* acc = dot_partials_.data() + 8 * omp_get_thread_num();
                                for (std::ptrdiff_t f = 0; f < len; f += 3)
                                  for (int k = 0; k < 3; ++k)
                                    acc[k] += wl[f + k] * static_cast<double>(xl[f + k]);
                              }
                            } else if (from_x) {
                              for (std::ptrdiff_t f = 0; f < len; ++f) {
                                rl[f] = rin[f] - v[f];
                                dl[f] = c * il[f] * rl[f];
                                xl[f] += dl[f];
                              }
                            } else {
                              for (std::ptrdiff_t f = 0; f < len; ++f) {
                                rl[f] = rin[f] - v[f];
                                dl[f] = a * dl[f] + c * il[f] * rl[f];
                                xl[f] += dl[f];
                              }
                            }
                          });
    return;
  }
  if (from_x) {
    sparse_chebyshev_step(L.Af, L.x.data(), nullptr, L.d.data(), nullptr, false, r_in, r,
                          L.inv_diag, 0, c);
    pending = true;
    return;
  }
  sparse_chebyshev_step(L.Af, L.d.data(), L.d.data(), L.d2.data(), L.x.data(), pending, r_in, r,
                        L.inv_diag, a, c);
  L.d.swap(L.d2);
  pending = false;
}

void MultigridHierarchy::smooth(Level& L, bool zero_initial) {
  // Chebyshev iteration on D⁻¹A over [lmin, lmax] (Adams, Brezina, Hu, Tuminaro 2003).
  // Each step is one pass fused with the operator apply before it (chebyshev_step); the
  // residual is only ever stored, never copied: the first step reads b.
  const Real lmax = L.lambda_max, lmin = static_cast<Real>(opt_.smoothing_range) * lmax;
  const Real theta = Real(0.5) * (lmax + lmin), delta = Real(0.5) * (lmax - lmin);
  const Real sigma = theta / delta;
  Real rho = Real(1) / sigma;
  const Real* r_in = L.b.data();
  bool pending = false;
  if (zero_initial) {
    // From x = 0 the residual is b: x = d = D⁻¹ b / θ, no operator apply.
    const int n = static_cast<int>(L.x.rows());
    const Real* b = L.b.data();
    Real* x = L.x.data();
    Real* d = L.d.data();
    const Real c = 1 / theta;
#pragma omp parallel for schedule(static) if (n > parallel_nodes)
    for (int i = 0; i < n; ++i) {
      const Real ci = c * L.inv_diag[i];
      for (std::ptrdiff_t f = 3 * static_cast<std::ptrdiff_t>(i); f < 3 * i + 3; ++f)
        x[f] = d[f] = ci * b[f];
    }
  } else {
    chebyshev_step(L, true, pending, r_in, 0, 1 / theta, opt_.smoothing_degree == 1, true);
    r_in = L.r.data();
  }
  for (int it = 1; it < opt_.smoothing_degree; ++it) {
    const Real rho_new = Real(1) / (Real(2) * sigma - rho);
    chebyshev_step(L, false, pending, r_in, rho_new * rho, Real(2) * rho_new / delta,
                   it + 1 == opt_.smoothing_degree, !zero_initial);
    r_in = L.r.data();
    rho = rho_new;
  }
  if (pending) L.x += L.d;  // degree 1 from a non-zero x on a sparse level
}

void MultigridHierarchy::cycle(int l) {
  Level& L = levels_[l];
  if (l + 1 == static_cast<int>(levels_.size())) {
    coarse_rhs_ = L.b.cast<double>();
    coarsest_.solveInPlace(coarse_rhs_);
    L.x = coarse_rhs_.cast<Real>();
    return;
  }
  Level& C = levels_[l + 1];
  smooth(L, true);
  // The finest level's transfers are matrix-free (grid_transfer.h) unless cubic.
  const bool transfer_free = L.matrix_free && !opt_.cubic;
  residual(L);
  if (transfer_free)
    restrict_to_coarse(L.dims, C.dims, L.r.data(), C.b.data());
  else
    spmv(L.R, L.r, C.b, Mode::Assign);
  cycle(l + 1);
  // Further corrections (W-cycle) solve the same coarse problem again, for what the first
  // left. With Galerkin operators the restricted residual after x += P e is
  // Pᵀ(r − A P e) = b_c − A_c e, so they run on the coarse level alone: one coarse product
  // instead of a residual, a restriction and a prolongation on this level (which cost
  // 8× more). Above the coarsest level the first correction is already exact.
  const int corrections = corrections_[l];
  if (corrections > 1) {
    C.b0.swap(C.b);  // the coarse right-hand side, kept
    C.e.swap(C.x);   // the corrections so far
    for (int g = 1; g < corrections; ++g) {
      sparse_residual(C.Af, C.e.data(), C.b0.data(), C.b.data());
      cycle(l + 1);
      add(C.x, C.e);
    }
    C.e.swap(C.x);
    C.b0.swap(C.b);
  }
  if (transfer_free)
    prolong_add(L.dims, C.dims, pinned_.data(), C.x.data(), L.x.data());
  else
    spmv(L.P, C.x, L.x, Mode::Add);
  smooth(L, false);
}

void MultigridHierarchy::apply(FieldF& r, FieldF& z, const double* dot_with, double dots[3]) {
  // The caller's vectors become the finest level's for the cycle (swaps, not 3n copies;
  // the cycle only reads b).
  Level& F = levels_[0];
  dot_with_ = dots ? dot_with : nullptr;
  dot_done_ = false;
  dot_partials_.assign(8 * static_cast<size_t>(std::max(1, omp_get_max_threads())), 0.0);
  F.b.swap(r);
  cycle(0);
  F.b.swap(r);
  z.swap(F.x);
  dot_with_ = nullptr;
  if (!dots) return;
  dots[0] = dots[1] = dots[2] = 0;
  if (dot_done_) {
    for (size_t t = 0; t < dot_partials_.size(); t += 8)
      for (int k = 0; k < 3; ++k) dots[k] += dot_partials_[t + k];
    return;
  }
  // A single-level hierarchy ends with the dense solve, not a smoothing step.
  const Real* zp = z.data();
  for (std::ptrdiff_t f = 0; f < z.size(); ++f) dots[f % 3] += dot_with[f] * static_cast<double>(zp[f]);
}

std::int64_t MultigridHierarchy::operator_nonzeros() const {
  std::int64_t s = 0;
  for (const Level& L : levels_) s += L.A.nonZeros();
  return s;
}

}  // namespace lapis::hair_field::detail
