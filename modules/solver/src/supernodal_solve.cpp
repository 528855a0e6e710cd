#include "supernodal_solve.h"

#include <omp.h>

#include <algorithm>

#include "permuted_rows.h"
#include "tree_split.h"

namespace lapis::solver::detail {
namespace {

// Columns of a supernode's diagonal block handled as one serial triangular step; the rows
// below a panel are then updated (forward) or read (backward) in parallel in a top supernode.
constexpr int kPanel = 256;
// A panel's rectangular update worth splitting over threads (entries of L).
constexpr long long kParallelEntries = 1 << 16;

struct SupernodeView {
  const int* super;
  const int* pi;
  const int* px;
  const int* s;
  const double* x;
  const int* perm;
  int nsuper;
  int n;

  explicit SupernodeView(const cholmod_factor& L)
      : super(static_cast<const int*>(L.super)),
        pi(static_cast<const int*>(L.pi)),
        px(static_cast<const int*>(L.px)),
        s(static_cast<const int*>(L.s)),
        x(static_cast<const double*>(L.x)),
        perm(static_cast<const int*>(L.Perm)),
        nsuper(static_cast<int>(L.nsuper)),
        n(static_cast<int>(L.n)) {}

  int first_column(int k) const { return super[k]; }
  int columns(int k) const { return super[k + 1] - super[k]; }
  int rows(int k) const { return pi[k + 1] - pi[k]; }
  const int* row_index(int k) const { return s + pi[k]; }
  const double* block(int k) const { return x + px[k]; }  // rows(k) by columns(k), column-major
  // The supernode holding the smallest row below the diagonal block.
  int parent(int k, const std::vector<int>& supernode_of) const {
    if (rows(k) == columns(k)) return -1;
    const int* below = row_index(k) + columns(k);
    return supernode_of[static_cast<size_t>(*std::min_element(below, row_index(k) + rows(k)))];
  }
};

// A supernode's right-hand-side rows are gathered into a scratch block stored column by
// column (x + c·ldx is right-hand side c, indexed by the supernode's local row), so that the
// loops over rows run at unit stride in L and in x and vectorize. Local row j < columns(k) is
// the supernode's own column j. Width: M right-hand sides (M = 0: the run-time count m).
template <int M>
struct Width {
  int m;
  int get() const { return M > 0 ? M : m; }
};

// x_c[r] −= Σ_{j0 <= j < j0 + Q} L(r, j) x_c[j] for rows r in [r0, r1), every right-hand side c.
template <int Q, int M>
void subtract_columns_q(const double* Lb, int ld, int j0, int r0, int r1, double* x, int ldx, Width<M> width) {
  const double* l[Q];
  for (int t = 0; t < Q; ++t) l[t] = Lb + static_cast<size_t>(j0 + t) * ld;
  if constexpr (M > 0) {
    // Every right-hand side in one pass over the rows: each entry of L is loaded once for
    // all M of them (a pass per right-hand side loads it M times).
    double* xc[M];
    double y[Q][M];
    for (int c = 0; c < M; ++c) {
      xc[c] = x + static_cast<size_t>(c) * ldx;
      for (int t = 0; t < Q; ++t) y[t][c] = xc[c][j0 + t];
    }
#pragma omp simd
    for (int r = r0; r < r1; ++r)
      for (int c = 0; c < M; ++c) {
        double d = 0;
        for (int t = 0; t < Q; ++t) d += l[t][r] * y[t][c];
        xc[c][r] -= d;
      }
    return;
  }
  for (int c = 0; c < width.get(); ++c) {
    double* xc = x + static_cast<size_t>(c) * ldx;
    double y[Q];
    for (int t = 0; t < Q; ++t) y[t] = xc[j0 + t];
#pragma omp simd
    for (int r = r0; r < r1; ++r) {
      double d = 0;
      for (int t = 0; t < Q; ++t) d += l[t][r] * y[t];
      xc[r] -= d;
    }
  }
}

// x_c[r] −= Σ_{j0 <= j < j1} L(r, j) x_c[j] for rows r in [r0, r1), every right-hand side c:
// four columns of L at a time, each x row read and written once per four columns.
template <int M>
void subtract_columns(const double* Lb, int ld, int j0, int j1, int r0, int r1, double* x, int ldx, Width<M> width) {
  if (r0 >= r1) return;
  for_column_groups(j0, j1,
                    [&](auto q, int j) { subtract_columns_q<decltype(q)::value>(Lb, ld, j, r0, r1, x, ldx, width); });
}

// x_c[j] −= Σ_{r0 <= r < r1} L(r, j) x_c[r] for columns j in [j0, j0 + Q), every c; Q sums
// kept apart so that they are independent chains.
template <int Q, int M>
void subtract_transposed_q(const double* Lb, int ld, int j0, int r0, int r1, double* x, int ldx, Width<M> width) {
  const double* l[Q];
  for (int t = 0; t < Q; ++t) l[t] = Lb + static_cast<size_t>(j0 + t) * ld;
  for (int c = 0; c < width.get(); ++c) {
    double* xc = x + static_cast<size_t>(c) * ldx;
    double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
    const double* l0 = l[0];
    const double* l1 = l[Q > 1 ? 1 : 0];
    const double* l2 = l[Q > 2 ? 2 : 0];
    const double* l3 = l[Q > 3 ? 3 : 0];
#pragma omp simd reduction(+ : s0, s1, s2, s3)
    for (int r = r0; r < r1; ++r) {
      s0 += l0[r] * xc[r];
      if constexpr (Q > 1) s1 += l1[r] * xc[r];
      if constexpr (Q > 2) s2 += l2[r] * xc[r];
      if constexpr (Q > 3) s3 += l3[r] * xc[r];
    }
    const double sums[4] = {s0, s1, s2, s3};
    for (int t = 0; t < Q; ++t) xc[j0 + t] -= sums[t];
  }
}

// x_c[j] −= Σ_{r0 <= r < r1} L(r, j) x_c[r] for columns j in [j0, j1), every c.
template <int M>
void subtract_transposed(const double* Lb, int ld, int j0, int j1, int r0, int r1, double* x, int ldx, Width<M> width) {
  if (r0 >= r1) return;
  for_column_groups(
      j0, j1, [&](auto q, int j) { subtract_transposed_q<decltype(q)::value>(Lb, ld, j, r0, r1, x, ldx, width); });
}

// Where a forward update of a row below the diagonal block goes: the thread's own rows of Y
// (those of its subtree) or its private buffer for the shared ancestors.
struct ForwardTarget {
  double* Y;
  double* shared;
  const int* top_slot;
  int limit;
  double* row(int global_row, int w) const {
    return global_row <= limit ? Y + static_cast<size_t>(global_row) * w
                               : shared + static_cast<size_t>(top_slot[global_row]) * w;
  }
};

// Runs f(r0, r1) over [begin, end), split into chunks over the threads when `parallel`.
template <class F>
void for_chunks(int begin, int end, bool parallel, F f) {
  if (!parallel) return f(begin, end);
  const int chunks = 4 * core::parallel_threads();
  for_each_piece(chunks, [&](int t) {
    f(begin + static_cast<int>(static_cast<long long>(end - begin) * t / chunks),
      begin + static_cast<int>(static_cast<long long>(end - begin) * (t + 1) / chunks));
  });
}

// L_k y_k = b_k for supernode k, then the rows below it −= L_below y_k. x: the scratch block
// (ldx rows per right-hand side). parallel: split the rectangular updates over the threads
// (top supernodes).
template <int M>
void forward_supernode(const SupernodeView& v, int k, Width<M> width, const ForwardTarget& target, double* x, int ldx,
                       bool parallel) {
  const int w = width.get();
  const int nc = v.columns(k), nr = v.rows(k), ld = nr;
  const double* Lb = v.block(k);
  const int* rows = v.row_index(k);
  double* Yk = target.Y + static_cast<size_t>(v.first_column(k)) * w;
  for (int c = 0; c < w; ++c) {
    double* xc = x + static_cast<size_t>(c) * ldx;
    for (int r = 0; r < nc; ++r) xc[r] = Yk[static_cast<size_t>(r) * w + c];
    std::fill(xc + nc, xc + nr, 0.0);  // rows below accumulate −L_below y_k
  }
  for (int j0 = 0; j0 < nc; j0 += kPanel) {
    const int j1 = std::min(nc, j0 + kPanel);
    for (int j = j0; j < j1; ++j) {  // the panel's triangle, serially
      for (int c = 0; c < w; ++c) x[static_cast<size_t>(c) * ldx + j] /= Lb[static_cast<size_t>(j) * ld + j];
      subtract_columns(Lb, ld, j, j + 1, j + 1, j1, x, ldx, width);
    }
    // Every row below the panel: the rest of the diagonal block, then the rows below it.
    const bool split = parallel && static_cast<long long>(nr - j1) * (j1 - j0) > kParallelEntries;
    for_chunks(j1, nr, split, [&](int r0, int r1) { subtract_columns(Lb, ld, j0, j1, r0, r1, x, ldx, width); });
  }
  for (int r = 0; r < nr; ++r) {
    double* t = r < nc ? Yk + static_cast<size_t>(r) * w : target.row(rows[r], w);
    for (int c = 0; c < w; ++c) {
      const double value = x[static_cast<size_t>(c) * ldx + r];
      if (r < nc)
        t[c] = value;
      else
        t[c] += value;
    }
  }
}

// L_kᵀ x_k = y_k − L_belowᵀ x_below for supernode k (the rows below are solved already).
template <int M>
void backward_supernode(const SupernodeView& v, int k, Width<M> width, double* Y, double* x, int ldx, bool parallel) {
  const int w = width.get();
  const int nc = v.columns(k), nr = v.rows(k), ld = nr;
  const double* Lb = v.block(k);
  const int* rows = v.row_index(k);
  double* Yk = Y + static_cast<size_t>(v.first_column(k)) * w;
  for (int r = 0; r < nr; ++r) {
    const double* source = r < nc ? Yk + static_cast<size_t>(r) * w : Y + static_cast<size_t>(rows[r]) * w;
    for (int c = 0; c < w; ++c) x[static_cast<size_t>(c) * ldx + r] = source[c];
  }
  for (int j1 = nc; j1 > 0; j1 -= kPanel) {
    const int j0 = std::max(0, j1 - kPanel);
    const bool split = parallel && static_cast<long long>(nr - j1) * (j1 - j0) > kParallelEntries;
    for_chunks(j0, j1, split, [&](int c0, int c1) { subtract_transposed(Lb, ld, c0, c1, j1, nr, x, ldx, width); });
    for (int j = j1 - 1; j >= j0; --j) {  // the panel's triangle, serially
      subtract_transposed(Lb, ld, j, j + 1, j + 1, j1, x, ldx, width);
      for (int c = 0; c < w; ++c) x[static_cast<size_t>(c) * ldx + j] /= Lb[static_cast<size_t>(j) * ld + j];
    }
  }
  for (int r = 0; r < nc; ++r)
    for (int c = 0; c < w; ++c) Yk[static_cast<size_t>(r) * w + c] = x[static_cast<size_t>(c) * ldx + r];
}

template <int M>
void solve_rows(const SupernodeView& v, const SupernodalSchedule& s, double* Y, int m) {
  const Width<M> width{m};
  const int threads = static_cast<int>(s.subtrees.size());
  const size_t w = static_cast<size_t>(m);
  std::vector<std::vector<double>> shared(static_cast<size_t>(threads),
                                          std::vector<double>(static_cast<size_t>(s.top_columns) * w, 0.0));
  const int ldx = std::max(1, s.max_rows);
  std::vector<std::vector<double>> scratch(static_cast<size_t>(threads),
                                           std::vector<double>(static_cast<size_t>(ldx) * w));

  // L y = P b: the subtrees in parallel (their updates of the shared ancestors go to
  // per-thread buffers, summed afterwards), then the ancestors in order.
  for_each_piece(threads, [&](int t) {
    for (const auto& range : s.subtrees[static_cast<size_t>(t)]) {
      const ForwardTarget target{Y, shared[static_cast<size_t>(t)].data(), s.top_slot.data(), range.limit};
      for (int k = range.first; k <= range.last; ++k)
        forward_supernode(v, k, width, target, scratch[static_cast<size_t>(t)].data(), ldx, false);
    }
  });
  for (int k : s.top)
    for (int j = v.first_column(k); j < v.first_column(k + 1); ++j) {
      const size_t slot = static_cast<size_t>(s.top_slot[static_cast<size_t>(j)]);
      for (int t = 0; t < threads; ++t)
        for (size_t c = 0; c < w; ++c)
          Y[static_cast<size_t>(j) * w + c] += shared[static_cast<size_t>(t)][slot * w + c];
    }
  const ForwardTarget top_target{Y, nullptr, nullptr, v.n};
  for (int k : s.top) forward_supernode(v, k, width, top_target, scratch[0].data(), ldx, threads > 1);

  // Lᵀ x = y: the ancestors first, then the subtrees in parallel (they only read ancestors).
  for (auto it = s.top.rbegin(); it != s.top.rend(); ++it)
    backward_supernode(v, *it, width, Y, scratch[0].data(), ldx, threads > 1);
  for_each_piece(threads, [&](int t) {
    const auto& mine = s.subtrees[static_cast<size_t>(t)];
    for (auto range = mine.rbegin(); range != mine.rend(); ++range)
      for (int k = range->last; k >= range->first; --k)
        backward_supernode(v, k, width, Y, scratch[static_cast<size_t>(t)].data(), ldx, false);
  });
}

}  // namespace

SupernodalSchedule schedule_supernodes(const cholmod_factor& L, int threads) {
  const SupernodeView v(L);
  SupernodalSchedule s;
  s.threads = threads > 0 ? threads : omp_get_max_threads();
  std::vector<int> supernode_of(static_cast<size_t>(v.n));
  for (int k = 0; k < v.nsuper; ++k) {
    std::fill(supernode_of.begin() + v.first_column(k), supernode_of.begin() + v.first_column(k + 1), k);
    s.max_rows = std::max(s.max_rows, v.rows(k));
  }
  std::vector<int> parent(static_cast<size_t>(v.nsuper));
  std::vector<double> work(static_cast<size_t>(v.nsuper));
  for (int k = 0; k < v.nsuper; ++k) {
    parent[static_cast<size_t>(k)] = v.parent(k, supernode_of);
    work[static_cast<size_t>(k)] = static_cast<double>(v.rows(k)) * v.columns(k);
  }
  const TreeSplit split = split_tree(parent, work, s.threads);
  s.subtrees.assign(split.subtrees.size(), {});
  for (size_t t = 0; t < split.subtrees.size(); ++t)
    for (const auto& [first, root] : split.subtrees[t])
      s.subtrees[t].push_back({first, root, v.first_column(root + 1) - 1});
  s.top_slot.assign(static_cast<size_t>(v.n), -1);
  for (int k = 0; k < v.nsuper; ++k) {
    if (split.in_subtree[static_cast<size_t>(k)]) continue;
    s.top.push_back(k);
    for (int j = v.first_column(k); j < v.first_column(k + 1); ++j)
      s.top_slot[static_cast<size_t>(j)] = s.top_columns++;
  }
  return s;
}

DenseMatrix solve_supernodal_llt(const cholmod_factor& L, const SupernodalSchedule& schedule, const DenseMatrix& B) {
  const SupernodeView v(L);
  const int m = static_cast<int>(B.cols());
  return solve_permuted_rows(v.perm, B,
                             [&](double* Y, auto width) { solve_rows<decltype(width)::value>(v, schedule, Y, m); });
}

}  // namespace lapis::solver::detail
