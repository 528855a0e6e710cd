#include "simplicial_solve.h"

#include <omp.h>

#include <algorithm>
#include <numeric>
#include <queue>

namespace lapis::solver::detail {
namespace {

constexpr int kMaxBlock = 64;  // right-hand sides per pass
constexpr int kMaxRun = 8;     // columns per run

struct FactorView {
  const int* p;
  const int* i;
  const int* nz;
  const double* x;
  const int* perm;
  int n;

  explicit FactorView(const cholmod_factor& L)
      : p(static_cast<const int*>(L.p)), i(static_cast<const int*>(L.i)),
        nz(static_cast<const int*>(L.nz)), x(static_cast<const double*>(L.x)),
        perm(static_cast<const int*>(L.Perm)), n(static_cast<int>(L.n)) {}

  // Columns are sorted with the diagonal first, so the parent in the elimination tree is the
  // first off-diagonal row.
  int parent(int j) const { return nz[j] > 1 ? i[p[j] + 1] : -1; }
};

long long pattern_entries(const FactorView& f) {
  long long total = 0;
  for (int j = 0; j < f.n; ++j) total += f.nz[j];
  return total;
}

// Longest-processing-time assignment of subtrees (by weight) to `bins`; returns the heaviest
// bin's load and, in `bin_of`, each subtree's bin.
double assign_bins(const std::vector<int>& roots, const std::vector<double>& weight, int bins,
                   std::vector<int>& bin_of) {
  std::vector<int> order(roots.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return weight[static_cast<size_t>(roots[static_cast<size_t>(a)])] >
                                       weight[static_cast<size_t>(roots[static_cast<size_t>(b)])]; });
  std::vector<double> load(static_cast<size_t>(bins), 0.0);
  bin_of.assign(roots.size(), 0);
  for (int k : order) {
    const auto lightest = std::min_element(load.begin(), load.end()) - load.begin();
    bin_of[static_cast<size_t>(k)] = static_cast<int>(lightest);
    load[static_cast<size_t>(lightest)] += weight[static_cast<size_t>(roots[static_cast<size_t>(k)])];
  }
  return *std::max_element(load.begin(), load.end());
}

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
  threads = std::max(1, threads);
  SubtreeSchedule s;
  s.n = n;
  s.pattern_entries = pattern_entries(f);
  if (threads == 1 || n == 0) {  // one thread: every column in order, every row its own
    s.runs.assign(1, {});
    append_runs(f, 0, n - 1, n, s.runs[0]);
    s.top_slot.assign(static_cast<size_t>(n), -1);
    return s;
  }

  // Subtree weights (entries of L below each node) and children lists; children have smaller
  // indices than their parent, so one ascending sweep accumulates the weights.
  std::vector<double> weight(static_cast<size_t>(n));
  std::vector<int> child_start(static_cast<size_t>(n) + 1, 0), children(static_cast<size_t>(n));
  std::vector<int> roots;
  for (int j = 0; j < n; ++j) weight[static_cast<size_t>(j)] = f.nz[j];
  for (int j = 0; j < n; ++j) {
    const int parent = f.parent(j);
    if (parent < 0) {
      roots.push_back(j);
    } else {
      weight[static_cast<size_t>(parent)] += weight[static_cast<size_t>(j)];
      ++child_start[static_cast<size_t>(parent) + 1];
    }
  }
  std::partial_sum(child_start.begin(), child_start.end(), child_start.begin());
  {
    std::vector<int> fill(child_start.begin(), child_start.end() - 1);
    for (int j = 0; j < n; ++j)
      if (const int parent = f.parent(j); parent >= 0) children[static_cast<size_t>(fill[static_cast<size_t>(parent)]++)] = j;
  }
  // Postorder check: a subtree is the range [first_descendant, root] when its size matches.
  std::vector<double> subtree_size(static_cast<size_t>(n), 1.0);
  std::vector<int> first_descendant(static_cast<size_t>(n));
  std::iota(first_descendant.begin(), first_descendant.end(), 0);
  for (int j = 0; j < n; ++j)
    if (const int parent = f.parent(j); parent >= 0) {
      subtree_size[static_cast<size_t>(parent)] += subtree_size[static_cast<size_t>(j)];
      first_descendant[static_cast<size_t>(parent)] =
          std::min(first_descendant[static_cast<size_t>(parent)], first_descendant[static_cast<size_t>(j)]);
    }
  const double total = std::accumulate(roots.begin(), roots.end(), 0.0,
                                       [&](double a, int r) { return a + weight[static_cast<size_t>(r)]; });

  // Split the heaviest subtree at its first branching node until the subtrees balance over
  // the threads; the nodes split off (the separators' chains) are solved serially. Stop when
  // that serial part grows past a third of L: more splitting would only move work there.
  std::vector<int> frontier = roots, bin_of;
  double top_weight = 0;
  for (int splits = 0; splits < 256; ++splits) {
    const double max_load = assign_bins(frontier, weight, threads, bin_of);
    const double ideal = (total - top_weight) / threads;
    if (max_load <= 1.05 * ideal || top_weight > total / 3) break;
    const auto heaviest = std::max_element(frontier.begin(), frontier.end(), [&](int a, int b) {
      return weight[static_cast<size_t>(a)] < weight[static_cast<size_t>(b)];
    });
    int node = *heaviest;
    frontier.erase(heaviest);
    for (;;) {
      top_weight += f.nz[node];
      const int c0 = child_start[static_cast<size_t>(node)], c1 = child_start[static_cast<size_t>(node) + 1];
      if (c1 - c0 != 1) {
        frontier.insert(frontier.end(), children.begin() + c0, children.begin() + c1);
        break;
      }
      node = children[static_cast<size_t>(c0)];
    }
  }
  assign_bins(frontier, weight, threads, bin_of);

  // Each thread's subtrees, as column ranges; a subtree that is not contiguous (not
  // postordered) makes the row test `row <= limit` wrong: solve on one thread then.
  std::vector<std::vector<std::pair<int, int>>> ranges(static_cast<size_t>(threads));  // (first, root)
  for (size_t k = 0; k < frontier.size(); ++k) {
    const int root = frontier[k];
    const double size = subtree_size[static_cast<size_t>(root)];
    const int first = root - static_cast<int>(size) + 1;
    if (first < 0 || first_descendant[static_cast<size_t>(root)] != first)
      return schedule_subtrees(L, 1);
    ranges[static_cast<size_t>(bin_of[k])].emplace_back(first, root);
  }
  std::vector<char> in_subtree(static_cast<size_t>(n), 0);
  s.runs.assign(static_cast<size_t>(threads), {});
  for (size_t t = 0; t < ranges.size(); ++t) {
    std::sort(ranges[t].begin(), ranges[t].end());
    for (const auto& [first, root] : ranges[t]) {
      append_runs(f, first, root, root, s.runs[t]);
      std::fill(in_subtree.begin() + first, in_subtree.begin() + root + 1, 1);
    }
  }
  s.top_slot.assign(static_cast<size_t>(n), -1);
  for (int j = 0; j < n; ++j) {
    if (in_subtree[static_cast<size_t>(j)]) continue;
    s.top_slot[static_cast<size_t>(j)] = s.top_columns++;
    // Ancestors are solved serially after the subtrees: every row is "local" to them.
    int last = j;
    while (last + 1 < n && !in_subtree[static_cast<size_t>(last) + 1]) ++last;
    for (int k = j + 1; k <= last; ++k) s.top_slot[static_cast<size_t>(k)] = s.top_columns++;
    append_runs(f, j, last, n, s.top);
    j = last;
  }
  return s;
}

bool schedule_matches(const SubtreeSchedule& schedule, const cholmod_factor& L) {
  const FactorView f(L);
  return schedule.n == f.n && schedule.pattern_entries == pattern_entries(f);
}

namespace {

// The right-hand sides of one row are stored together (row-major Y with M columns; M = 0:
// the run-time width m), so a column of L is streamed once for all of them. In a run of K
// columns, column first+s keeps its entries for rows first+s+1 .. first+K-1 (inside the run)
// at offsets 1 .. K-1-s, and then the rows it shares with the run's last column.
template <int M, int K>
void forward_run(const FactorView& f, const ColumnRun& run, double* Y, int m, double* shared,
                 const int* top_slot) {
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
    case 1: forward_run<M, 1>(f, run, Y, m, shared, top_slot); break;
    case 2: forward_run<M, 2>(f, run, Y, m, shared, top_slot); break;
    case 3: forward_run<M, 3>(f, run, Y, m, shared, top_slot); break;
    case 4: forward_run<M, 4>(f, run, Y, m, shared, top_slot); break;
    case 5: forward_run<M, 5>(f, run, Y, m, shared, top_slot); break;
    case 6: forward_run<M, 6>(f, run, Y, m, shared, top_slot); break;
    case 7: forward_run<M, 7>(f, run, Y, m, shared, top_slot); break;
    default: forward_run<M, 8>(f, run, Y, m, shared, top_slot); break;
  }
}

template <int M>
void backward(const FactorView& f, const ColumnRun& run, double* Y, int m) {
  switch (run.count) {
    case 1: backward_run<M, 1>(f, run, Y, m); break;
    case 2: backward_run<M, 2>(f, run, Y, m); break;
    case 3: backward_run<M, 3>(f, run, Y, m); break;
    case 4: backward_run<M, 4>(f, run, Y, m); break;
    case 5: backward_run<M, 5>(f, run, Y, m); break;
    case 6: backward_run<M, 6>(f, run, Y, m); break;
    case 7: backward_run<M, 7>(f, run, Y, m); break;
    default: backward_run<M, 8>(f, run, Y, m); break;
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
#pragma omp parallel for num_threads(threads) schedule(static, 1)
  for (int t = 0; t < threads; ++t)
    for (const ColumnRun& run : s.runs[static_cast<size_t>(t)])
      forward<M>(f, run, Y, m, shared[static_cast<size_t>(t)].data(), s.top_slot.data());
  for (int j = 0; j < f.n; ++j) {
    const int slot = s.top_slot[static_cast<size_t>(j)];
    if (slot < 0) continue;
    for (int t = 0; t < threads; ++t)
      for (size_t c = 0; c < width; ++c)
        Y[static_cast<size_t>(j) * width + c] += shared[static_cast<size_t>(t)][static_cast<size_t>(slot) * width + c];
  }
  for (const ColumnRun& run : s.top) forward<M>(f, run, Y, m, nullptr, s.top_slot.data());

  // D z = y.
#pragma omp parallel for num_threads(threads)
  for (int j = 0; j < f.n; ++j) {
    const double d = f.x[f.p[j]];
    for (size_t c = 0; c < width; ++c) Y[static_cast<size_t>(j) * width + c] /= d;
  }

  // Lᵀ x = z: the ancestors first, then the subtrees in parallel (they only read ancestors).
  for (auto it = s.top.rbegin(); it != s.top.rend(); ++it) backward<M>(f, *it, Y, m);
#pragma omp parallel for num_threads(threads) schedule(static, 1)
  for (int t = 0; t < threads; ++t) {
    const auto& mine = s.runs[static_cast<size_t>(t)];
    for (auto it = mine.rbegin(); it != mine.rend(); ++it) backward<M>(f, *it, Y, m);
  }
}

}  // namespace

DenseMatrix solve_simplicial_ldlt(const cholmod_factor& L, const SubtreeSchedule& schedule,
                                  const DenseMatrix& B) {
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
  std::vector<double> Y(static_cast<size_t>(n) * static_cast<size_t>(m));
  for (int j = 0; j < n; ++j) {
    const int row = f.perm ? f.perm[j] : j;
    for (int c = 0; c < m; ++c) Y[static_cast<size_t>(j) * static_cast<size_t>(m) + static_cast<size_t>(c)] = B(row, c);
  }
  // The common widths get kernels with the width fixed at compile time.
  switch (m) {
    case 1: solve_blocks<1>(f, schedule, Y.data(), m); break;
    case 2: solve_blocks<2>(f, schedule, Y.data(), m); break;
    case 3: solve_blocks<3>(f, schedule, Y.data(), m); break;
    case 4: solve_blocks<4>(f, schedule, Y.data(), m); break;
    default: solve_blocks<0>(f, schedule, Y.data(), m); break;
  }
  DenseMatrix X(n, m);
  for (int j = 0; j < n; ++j) {
    const int row = f.perm ? f.perm[j] : j;
    for (int c = 0; c < m; ++c) X(row, c) = Y[static_cast<size_t>(j) * static_cast<size_t>(m) + static_cast<size_t>(c)];
  }
  return X;
}

}  // namespace lapis::solver::detail
