#include "simplicial_solve.h"

#include <omp.h>

#include <algorithm>

#include "permuted_rows.h"
#include "simplicial_view.h"
#include "tree_split.h"

namespace lapis::solver::detail {
namespace {

constexpr int kMaxBlock = 64;  // right-hand sides per pass
constexpr int kMaxRun = 8;     // columns per run

using FactorView = SimplicialView<const double>;

// Column j + 1 continues a run ending at column j when it is j's parent and j's pattern is
// exactly {j} ∪ pattern(j + 1) (checked entry by entry: it is what the kernels rely on).
bool continues_run(const FactorView& f, int j) {
  if (f.parent(j) != j + 1 || f.nz[j] != f.nz[j + 1] + 1) return false;
  return std::equal(f.i + f.p[j] + 1, f.i + f.p[j] + f.nz[j], f.i + f.p[j + 1]);
}

// Runs of at most kMaxRun columns covering [first, last]; rows above `limit` are shared.
void append_runs(const FactorView& f, int first, int last, int limit, std::vector<ColumnRun>& out) {
  for (int j = first; j <= last;) {
    ColumnRun run{j, 1, limit};
    while (run.count < kMaxRun && j + run.count <= last && continues_run(f, j + run.count - 1)) ++run.count;
    out.push_back(run);
    j += run.count;
  }
}

}  // namespace

SubtreeSchedule schedule_subtrees(const cholmod_factor& L, int threads) {
  const FactorView f(L);
  const int n = f.n;
  SubtreeSchedule s;
  s.n = n;
  s.pattern_entries = f.entries();
  std::vector<int> parent(static_cast<size_t>(n));
  std::vector<double> work(static_cast<size_t>(n));
  for (int j = 0; j < n; ++j) {
    parent[static_cast<size_t>(j)] = f.parent(j);
    work[static_cast<size_t>(j)] = f.nz[j];
  }
  const TreeSplit split = split_tree(parent, work, threads);
  s.runs.assign(split.subtrees.size(), {});
  for (size_t t = 0; t < split.subtrees.size(); ++t)
    for (const auto& [first, root] : split.subtrees[t]) append_runs(f, first, root, root, s.runs[t]);
  s.top_slot.assign(static_cast<size_t>(n), -1);
  for (int j = 0; j < n; ++j) {
    if (split.in_subtree[static_cast<size_t>(j)]) continue;
    // Ancestors are solved serially after the subtrees: every row is "local" to them.
    int last = j;
    while (last + 1 < n && !split.in_subtree[static_cast<size_t>(last) + 1]) ++last;
    for (int k = j; k <= last; ++k) s.top_slot[static_cast<size_t>(k)] = s.top_columns++;
    append_runs(f, j, last, n, s.top);
    j = last;
  }
  return s;
}

bool schedule_matches(const SubtreeSchedule& schedule, const cholmod_factor& L) {
  const FactorView f(L);
  return schedule.n == f.n && schedule.pattern_entries == f.entries();
}

namespace {

// The right-hand sides of one row are stored together (row-major Y with M columns; M = 0:
// the run-time width m), so a column of L is streamed once for all of them. In a run of K
// columns, column first+s keeps its entries for rows first+s+1 .. first+K-1 (inside the run)
// at offsets 1 .. K-1-s, and then the rows it shares with the run's last column.
template <int M, int K>
void forward_run(const FactorView& f, const ColumnRun& run, double* Y, int m, double* shared, const int* top_slot) {
  constexpr int kCols = M > 0 ? M : kMaxBlock;
  const int cols = M > 0 ? M : m;
  const int j0 = run.first;
  double y[K][kCols];
  const double* lx[K];
  for (int s = 0; s < K; ++s) {
    double* ys = Y + static_cast<size_t>(j0 + s) * static_cast<size_t>(cols);
    for (int c = 0; c < cols; ++c) y[s][c] = ys[c];
    for (int t = s + 1; t < K; ++t) {  // inside the run, in order
      const double l = f.x[f.p[j0 + s] + (t - s)];
      double* yt = Y + static_cast<size_t>(j0 + t) * static_cast<size_t>(cols);
      for (int c = 0; c < cols; ++c) yt[c] -= l * y[s][c];
    }
  }
  for (int s = 0; s < K; ++s) lx[s] = f.x + f.p[j0 + s] + (K - s);
  const int last = j0 + K - 1;
  const int* rows = f.i + f.p[last] + 1;
  const int count = f.nz[last] - 1;
  for (int r = 0; r < count; ++r) {
    const int row = rows[r];
    double* target = row <= run.limit ? Y + static_cast<size_t>(row) * static_cast<size_t>(cols)
                                      : shared + static_cast<size_t>(top_slot[row]) * static_cast<size_t>(cols);
    for (int c = 0; c < cols; ++c) {
      double d = 0;
      for (int s = 0; s < K; ++s) d += lx[s][r] * y[s][c];
      target[c] -= d;
    }
  }
}

template <int M, int K>
void backward_run(const FactorView& f, const ColumnRun& run, double* Y, int m) {
  constexpr int kCols = M > 0 ? M : kMaxBlock;
  const int cols = M > 0 ? M : m;
  const int j0 = run.first;
  const int last = j0 + K - 1;
  const int* rows = f.i + f.p[last] + 1;
  const int count = f.nz[last] - 1;
  double sum[K][kCols] = {};
  const double* lx[K];
  for (int s = 0; s < K; ++s) lx[s] = f.x + f.p[j0 + s] + (K - s);
  for (int r = 0; r < count; ++r) {
    const double* x = Y + static_cast<size_t>(rows[r]) * static_cast<size_t>(cols);
    for (int s = 0; s < K; ++s)
      for (int c = 0; c < cols; ++c) sum[s][c] += lx[s][r] * x[c];
  }
  for (int s = K - 1; s >= 0; --s) {
    double* ys = Y + static_cast<size_t>(j0 + s) * static_cast<size_t>(cols);
    for (int t = s + 1; t < K; ++t) {
      const double l = f.x[f.p[j0 + s] + (t - s)];
      const double* yt = Y + static_cast<size_t>(j0 + t) * static_cast<size_t>(cols);
      for (int c = 0; c < cols; ++c) sum[s][c] += l * yt[c];
    }
    for (int c = 0; c < cols; ++c) ys[c] -= sum[s][c];
  }
}

template <int M>
void forward(const FactorView& f, const ColumnRun& run, double* Y, int m, double* shared, const int* top_slot) {
  switch (run.count) {
    case 1:
      forward_run<M, 1>(f, run, Y, m, shared, top_slot);
      break;
    case 2:
      forward_run<M, 2>(f, run, Y, m, shared, top_slot);
      break;
    case 3:
      forward_run<M, 3>(f, run, Y, m, shared, top_slot);
      break;
    case 4:
      forward_run<M, 4>(f, run, Y, m, shared, top_slot);
      break;
    case 5:
      forward_run<M, 5>(f, run, Y, m, shared, top_slot);
      break;
    case 6:
      forward_run<M, 6>(f, run, Y, m, shared, top_slot);
      break;
    case 7:
      forward_run<M, 7>(f, run, Y, m, shared, top_slot);
      break;
    default:
      forward_run<M, 8>(f, run, Y, m, shared, top_slot);
      break;
  }
}

template <int M>
void backward(const FactorView& f, const ColumnRun& run, double* Y, int m) {
  switch (run.count) {
    case 1:
      backward_run<M, 1>(f, run, Y, m);
      break;
    case 2:
      backward_run<M, 2>(f, run, Y, m);
      break;
    case 3:
      backward_run<M, 3>(f, run, Y, m);
      break;
    case 4:
      backward_run<M, 4>(f, run, Y, m);
      break;
    case 5:
      backward_run<M, 5>(f, run, Y, m);
      break;
    case 6:
      backward_run<M, 6>(f, run, Y, m);
      break;
    case 7:
      backward_run<M, 7>(f, run, Y, m);
      break;
    default:
      backward_run<M, 8>(f, run, Y, m);
      break;
  }
}

template <int M>
void solve_blocks(const FactorView& f, const SubtreeSchedule& s, double* Y, int m) {
  const int threads = static_cast<int>(s.runs.size());
  const size_t width = static_cast<size_t>(m);
  std::vector<std::vector<double>> shared(static_cast<size_t>(threads),
                                          std::vector<double>(static_cast<size_t>(s.top_columns) * width, 0.0));

  // L y = P b: the subtrees in parallel (their updates of the shared ancestors go to
  // per-thread buffers, summed afterwards), then the ancestors in order.
  for_each_piece(threads, [&](int t) {
    for (const ColumnRun& run : s.runs[static_cast<size_t>(t)])
      forward<M>(f, run, Y, m, shared[static_cast<size_t>(t)].data(), s.top_slot.data());
  });
  for (int j = 0; j < f.n; ++j) {
    const int slot = s.top_slot[static_cast<size_t>(j)];
    if (slot < 0) continue;
    for (int t = 0; t < threads; ++t)
      for (size_t c = 0; c < width; ++c)
        Y[static_cast<size_t>(j) * width + c] += shared[static_cast<size_t>(t)][static_cast<size_t>(slot) * width + c];
  }
  for (const ColumnRun& run : s.top) forward<M>(f, run, Y, m, nullptr, s.top_slot.data());

  // D z = y.
  core::parallel_for(0, f.n, 4096, [&](std::ptrdiff_t lo, std::ptrdiff_t hi) {
    for (std::ptrdiff_t j = lo; j < hi; ++j) {
      const double d = f.x[f.p[j]];
      for (size_t c = 0; c < width; ++c) Y[static_cast<size_t>(j) * width + c] /= d;
    }
  });

  // Lᵀ x = z: the ancestors first, then the subtrees in parallel (they only read ancestors).
  for (auto it = s.top.rbegin(); it != s.top.rend(); ++it) backward<M>(f, *it, Y, m);
  for_each_piece(threads, [&](int t) {
    const auto& mine = s.runs[static_cast<size_t>(t)];
    for (auto it = mine.rbegin(); it != mine.rend(); ++it) backward<M>(f, *it, Y, m);
  });
}

}  // namespace

DenseMatrix solve_simplicial_ldlt(const cholmod_factor& L, const SubtreeSchedule& schedule, const DenseMatrix& B) {
  const FactorView f(L);
  const int n = f.n;
  const int m = static_cast<int>(B.cols());
  if (m > kMaxBlock) {  // the backward kernel sums in a stack buffer of kMaxBlock columns
    DenseMatrix X(n, m);
    for (int c0 = 0; c0 < m; c0 += kMaxBlock) {
      const int w = std::min(kMaxBlock, m - c0);
      X.middleCols(c0, w) = solve_simplicial_ldlt(L, schedule, B.middleCols(c0, w));
    }
    return X;
  }
  return solve_permuted_rows(f.perm, B,
                             [&](double* Y, auto width) { solve_blocks<decltype(width)::value>(f, schedule, Y, m); });
}

}  // namespace lapis::solver::detail
