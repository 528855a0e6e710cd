// Building the multigrid hierarchy (prolongations, Galerkin levels, smoother bounds, the
// coarsest factor) and updating it in place when constraints change; the cycle that runs on
// it is in multigrid_cycle.cpp.
#include "multigrid_hierarchy.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <unordered_map>

#include "grid_stencil.h"
#include "grid_transfer.h"
#include "lapis/core/error.h"
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

}  // namespace

MultigridHierarchy::MultigridHierarchy(const Grid& grid, const Eigen::VectorXd& weights, MultigridOptions options)
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
    corrections_[l] = l == 0                ? opt_.cycle_index
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

void MultigridHierarchy::factor_coarsest() { coarsest_.compute(Eigen::MatrixXd(levels_.back().A)); }

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
        for (RowSparseD::InnerIterator b(L.Pd, e.j); b; ++b) acc[a.col() * nc + b.col()] += a.value() * e.v * b.value();
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
      throw SolverFailure("hair_field::MultigridHierarchy::add_to_diagonal(): entry (" + std::to_string(e.i) + ", " +
                          std::to_string(e.j) + ") outside the Galerkin pattern of level " + std::to_string(l));
    L.A.valuePtr()[p] += e.v;
    rows.push_back(e.i);
  }
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  for (int r : rows) refresh_row(L, r);
  L.lambda_max = L.gershgorin.maxCoeff();
}

void MultigridHierarchy::free_set_change(int s, double sign, std::unordered_map<long long, double>& acc) const {
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

std::int64_t MultigridHierarchy::operator_nonzeros() const {
  std::int64_t s = 0;
  for (const Level& L : levels_) s += L.A.nonZeros();
  return s;
}

}  // namespace lapis::hair_field::detail
