#include "diagonal_updown.h"

#include <immintrin.h>
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>

#include "simplicial_view.h"
#include "tree_split.h"

namespace lapis::solver::detail {
namespace {

constexpr int kTermsPerSweep = 16;  // terms sharing one sweep (bits of a column's term mask)

// A column's pivot as its row updates read it: the terms that change the column and their p
// and β (Method C1).
struct PivotSlot {
  int active = 0;  // terms in term[], or -1 when a pivot would not stay positive
  int term[kTermsPerSweep];
  double p[kTermsPerSweep], beta[kTermsPerSweep];
};

constexpr int kUnitsPerThread = 4;  // subtrees per thread to deal by work (more: a bigger top)
constexpr int kSplitRows = 512;     // a shared ancestor's rows are split over the threads from here

using Factor = SimplicialView<double>;

// The terms that change a column, as the row kernel reads them.
struct Terms {
  double* w[kTermsPerSweep];
  const double* p;
  const double* beta;
  int count;
};

// Four rows l[0..3] at consecutive workspace rows `first`..`first` + 3: for each term k in
// order, w_k(i) −= p_k l_i, then l_i += β_k w_k(i) (Method C1's inner loop).
__attribute__((target("avx2,fma"))) inline void four_consecutive(double* l, int first, const Terms& t) {
  __m256d lv = _mm256_loadu_pd(l);
  for (int k = 0; k < t.count; ++k) {
    double* wk = t.w[k] + first;
    const __m256d wv = _mm256_fnmadd_pd(_mm256_set1_pd(t.p[k]), lv, _mm256_loadu_pd(wk));
    _mm256_storeu_pd(wk, wv);
    lv = _mm256_fmadd_pd(_mm256_set1_pd(t.beta[k]), wv, lv);
  }
  _mm256_storeu_pd(l, lv);
}

__attribute__((target("avx2,fma"))) inline void one_row(double* l, int row, const Terms& t) {
  double li = *l;
  for (int k = 0; k < t.count; ++k) {
    double& wi = t.w[k][row];
    wi = std::fma(-t.p[k], li, wi);
    li = std::fma(t.beta[k], wi, li);
  }
  *l = li;
}

// Eight consecutive rows: two independent chains of four, interleaved so that one's
// multiply-adds wait out the other's latency.
__attribute__((target("avx2,fma"))) inline void eight_consecutive(double* l, int first, const Terms& t) {
  __m256d l0 = _mm256_loadu_pd(l), l1 = _mm256_loadu_pd(l + 4);
  for (int k = 0; k < t.count; ++k) {
    double* wk = t.w[k] + first;
    const __m256d p = _mm256_set1_pd(t.p[k]), beta = _mm256_set1_pd(t.beta[k]);
    const __m256d w0 = _mm256_fnmadd_pd(p, l0, _mm256_loadu_pd(wk));
    const __m256d w1 = _mm256_fnmadd_pd(p, l1, _mm256_loadu_pd(wk + 4));
    _mm256_storeu_pd(wk, w0);
    _mm256_storeu_pd(wk + 4, w1);
    l0 = _mm256_fmadd_pd(beta, w0, l0);
    l1 = _mm256_fmadd_pd(beta, w1, l1);
  }
  _mm256_storeu_pd(l, l0);
  _mm256_storeu_pd(l + 4, l1);
}

// (The masked form: the plain one starts from an undefined register, which GCC warns about.)
__attribute__((target("avx2,fma"))) inline __m256d gather(const double* base, __m128i index) {
  return _mm256_mask_i32gather_pd(_mm256_setzero_pd(), base, index, _mm256_castsi256_pd(_mm256_set1_epi64x(-1)), 8);
}

// Four rows anywhere: the workspace gathered, and stored lane by lane (AVX2 has no scatter).
__attribute__((target("avx2,fma"))) inline void four_scattered(double* l, const int* rows, const Terms& t) {
  __m256d lv = _mm256_loadu_pd(l);
  const __m128i index = _mm_loadu_si128(reinterpret_cast<const __m128i*>(rows));
  alignas(32) double lanes[4];
  for (int k = 0; k < t.count; ++k) {
    const __m256d wv = _mm256_fnmadd_pd(_mm256_set1_pd(t.p[k]), lv, gather(t.w[k], index));
    _mm256_store_pd(lanes, wv);
    for (int a = 0; a < 4; ++a) t.w[k][rows[a]] = lanes[a];
    lv = _mm256_fmadd_pd(_mm256_set1_pd(t.beta[k]), wv, lv);
  }
  _mm256_storeu_pd(l, lv);
}

// All rows below the diagonal of a column. Rows are independent, so they go four or eight at a
// time; consecutive row indices (the rule near the top of a nested-dissection tree: the
// separators' own rows) read and write the workspace directly. Rows are ascending and
// distinct, so rows[r + 7] − rows[r] = 7 means eight consecutive ones.
__attribute__((target("avx2,fma"))) void update_rows(const int* rows, double* l, int count, const Terms& t) {
  int r = 0;
  while (r + 4 <= count) {
    if (r + 8 <= count && rows[r + 7] - rows[r] == 7) {
      eight_consecutive(l + r, rows[r], t);
      r += 8;
    } else {
      if (rows[r + 3] - rows[r] == 3)
        four_consecutive(l + r, rows[r], t);
      else
        four_scattered(l + r, rows + r, t);
      r += 4;
    }
  }
  for (; r < count; ++r) one_row(l + r, rows[r], t);
}

// Column j's pivot, term after term (d̄ = d + α p², β = α p / d̄, α ← α d / d̄): updates the
// α of the terms that pass column j, fills `slot` (active = −1 if a pivot would not stay
// positive) and returns the new D(j) (not written to the factor).
double pivot(const Factor& f, int j, unsigned term_bits, double* alpha, const double* w_all, size_t n,
             PivotSlot& slot) {
  double d = f.x[f.p[j]];
  int active = 0;
  for (unsigned bits = term_bits; bits != 0; bits &= bits - 1) {
    const int t = __builtin_ctz(bits);
    const double pj = w_all[static_cast<size_t>(t) * n + static_cast<size_t>(j)];
    if (pj == 0) continue;  // this term leaves the column as it is
    const double dbar = d + alpha[t] * pj * pj;
    if (!(dbar > 0) || !std::isfinite(dbar)) {
      slot.active = -1;
      return d;
    }
    slot.term[active] = t;
    slot.p[active] = pj;
    slot.beta[active] = alpha[t] * pj / dbar;
    alpha[t] *= d / dbar;
    d = dbar;
    ++active;
  }
  slot.active = active;
  return d;
}

Terms terms_of(const PivotSlot& slot, double* w_all, size_t n) {
  Terms t{{}, slot.p, slot.beta, slot.active};
  for (int k = 0; k < slot.active; ++k) t.w[k] = w_all + static_cast<size_t>(slot.term[k]) * n;
  return t;
}

// The sweep's columns: the union of the terms' elimination-tree paths, ascending, with the
// terms that pass each column marked in work.terms_at.
std::vector<int> path_union(const std::pair<int, double>* terms, int m, DiagonalUpdownWork& work) {
  std::vector<int> columns;
  for (int t = 0; t < m; ++t)
    for (int j = terms[t].first; j >= 0; j = work.parent[static_cast<size_t>(j)]) {
      if (work.terms_at[static_cast<size_t>(j)] == 0) columns.push_back(j);
      work.terms_at[static_cast<size_t>(j)] |= 1u << t;
    }
  std::sort(columns.begin(), columns.end());
  return columns;
}

// The columns of the shared ancestors (no subtree owns them), and the thread of each subtree.
struct Deal {
  std::vector<int> top, thread_of;
};

// The subtrees' work in this sweep (rows × terms), dealt to the threads heaviest first: where
// the terms start decides it, not the subtrees' sizes.
Deal deal_subtrees(const Factor& f, const std::vector<int>& columns, const DiagonalUpdownWork& work) {
  Deal deal{{}, std::vector<int>(static_cast<size_t>(work.units), 0)};
  std::vector<double> unit_work(static_cast<size_t>(work.units), 0.0);
  for (int j : columns) {
    const int u = work.owner[static_cast<size_t>(j)];
    if (u < 0)
      deal.top.push_back(j);
    else
      unit_work[static_cast<size_t>(u)] +=
          static_cast<double>(f.nz[j]) * __builtin_popcount(work.terms_at[static_cast<size_t>(j)]);
  }
  std::vector<int> order(static_cast<size_t>(work.units));
  for (int u = 0; u < work.units; ++u) order[static_cast<size_t>(u)] = u;
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return unit_work[static_cast<size_t>(a)] > unit_work[static_cast<size_t>(b)]; });
  std::vector<double> load(static_cast<size_t>(work.threads), 0.0);
  for (int u : order) {
    const auto lightest = std::min_element(load.begin(), load.end()) - load.begin();
    deal.thread_of[static_cast<size_t>(u)] = static_cast<int>(lightest);
    load[static_cast<size_t>(lightest)] += unit_work[static_cast<size_t>(u)];
  }
  return deal;
}

// What the threads of one sweep share.
struct Sweep {
  Factor& f;
  DiagonalUpdownWork& work;
  const std::vector<int>& columns;
  const Deal& deal;
  double* alpha;  // each term's α
  double* w_all;  // the terms' w vectors, n apart
  size_t n;
  std::atomic<std::ptrdiff_t>& failed;  // the column where a pivot would not stay positive

  // Pivots column j with the given α and updates all its rows; false if the pivot fails.
  bool column(int j, double* alpha_of, PivotSlot& slot) {
    const double d = pivot(f, j, work.terms_at[static_cast<size_t>(j)], alpha_of, w_all, n, slot);
    if (slot.active < 0) return false;
    f.x[f.p[j]] = d;
    if (slot.active > 0) update_rows(f.i + f.p[j] + 1, f.x + f.p[j] + 1, f.nz[j] - 1, terms_of(slot, w_all, n));
    return true;
  }
};

// The subtrees: each thread its own, columns in ascending order. A term's α changes only in
// the subtree where it starts, so the shared α array has one writer per entry.
void sweep_subtrees(Sweep& s, int me, int threads, PivotSlot& slot) {
  for (int j : s.columns) {
    const int u = s.work.owner[static_cast<size_t>(j)];
    // (Modulo the team: a nested call may get fewer threads than asked for.)
    if (u < 0 || s.deal.thread_of[static_cast<size_t>(u)] % threads != me) continue;
    if (!s.column(j, s.alpha, slot)) {
      s.failed = j;
      return;
    }
  }
}

// The shared ancestors in order, called by every thread of the team. A long column's rows are
// split over the threads: every thread takes the same pivot (the same arithmetic on the same
// data, with its own α), so one barrier per column suffices, and D(j) is written back by
// thread 0 once that barrier is passed and no thread reads it any more. A run of short columns
// goes to thread 0 alone, with one barrier after the run (a barrier per short column would
// cost more than its rows, and far more when the machine is busy and a waiting thread loses
// its core).
void sweep_ancestors(Sweep& s, int me, int threads, PivotSlot& slot) {
  double my_alpha[kTermsPerSweep];
  std::copy(s.alpha, s.alpha + kTermsPerSweep, my_alpha);
  const std::vector<int>& top = s.deal.top;
  auto rows_of = [&](int j) { return s.f.nz[j] - 1; };
  for (size_t k = 0; k < top.size() && s.failed < 0;) {
    if (rows_of(top[k]) < kSplitRows) {
      size_t end = k;
      while (end < top.size() && rows_of(top[end]) < kSplitRows) ++end;
      if (me == 0) {
        for (; k < end; ++k)
          if (!s.column(top[k], my_alpha, slot)) {
            s.failed = top[k];
            break;
          }
        std::copy(my_alpha, my_alpha + kTermsPerSweep, s.alpha);
      }
#pragma omp barrier
      std::copy(s.alpha, s.alpha + kTermsPerSweep, my_alpha);
      k = end;
#pragma omp barrier
      continue;
    }
    const int j = top[k++];
    const double d = pivot(s.f, j, s.work.terms_at[static_cast<size_t>(j)], my_alpha, s.w_all, s.n, slot);
    if (slot.active < 0) {  // the same on every thread
      if (me == 0) s.failed = j;
      break;
    }
    if (slot.active > 0) {
      const int count = rows_of(j);
      const int share = ((count + threads - 1) / threads + 7) & ~7;  // groups of eight rows
      const int r0 = std::min(count, me * share), r1 = std::min(count, r0 + share);
      if (r1 > r0)
        update_rows(s.f.i + s.f.p[j] + 1 + r0, s.f.x + s.f.p[j] + 1 + r0, r1 - r0, terms_of(slot, s.w_all, s.n));
    }
#pragma omp barrier
    if (me == 0) s.f.x[s.f.p[j]] = d;
  }
}

// One sweep for up to kTermsPerSweep terms (permuted column, δ).
std::ptrdiff_t sweep(Factor& f, const std::pair<int, double>* terms, int m, DiagonalUpdownWork& work) {
  const size_t n = static_cast<size_t>(f.n);
  const std::vector<int> columns = path_union(terms, m, work);
  double alpha[kTermsPerSweep] = {};
  for (int t = 0; t < m; ++t) {
    work.w[static_cast<size_t>(t) * n + static_cast<size_t>(terms[t].first)] = std::sqrt(std::abs(terms[t].second));
    alpha[t] = terms[t].second > 0 ? 1.0 : -1.0;  // σ: update or downdate
  }
  const Deal deal = deal_subtrees(f, columns, work);
  std::atomic<std::ptrdiff_t> failed{-1};
  Sweep s{f, work, columns, deal, alpha, work.w.data(), n, failed};
#pragma omp parallel num_threads(work.threads)
  {
    const int me = omp_get_thread_num(), threads = omp_get_num_threads();
    PivotSlot slot;
    sweep_subtrees(s, me, threads, slot);
#pragma omp barrier
    if (failed < 0) sweep_ancestors(s, me, threads, slot);
  }
  // Every row a column touches is one of its ancestors, so on the paths: clear just those.
  for (int j : columns) {
    for (int t = 0; t < m; ++t) work.w[static_cast<size_t>(t) * n + static_cast<size_t>(j)] = 0;
    work.terms_at[static_cast<size_t>(j)] = 0;
  }
  return failed;
}

}  // namespace

bool diagonal_updown_available() {
  static const bool available = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  return available;
}

std::ptrdiff_t diagonal_updown(cholmod_factor& L, const std::vector<std::pair<int, double>>& deltas,
                               DiagonalUpdownWork& work, int threads) {
  Factor f(L);
  const size_t n = static_cast<size_t>(f.n);
  threads = threads > 0 ? threads : omp_get_max_threads();
  // A general update (cholmod_updown) may have added fill and changed the elimination tree
  // since the split was made: rebuild it then.
  const long long entries_of_L = f.entries();
  if (work.w.size() != kTermsPerSweep * n || work.threads != threads || work.pattern_entries != entries_of_L) {
    work.pattern_entries = entries_of_L;
    work.w.assign(kTermsPerSweep * n, 0.0);
    work.terms_at.assign(n, 0u);
    work.parent.resize(n);
    std::vector<double> entries(n);
    for (size_t j = 0; j < n; ++j) {
      work.parent[j] = f.parent(static_cast<int>(j));
      entries[j] = f.nz[j];
    }
    const TreeSplit split = split_tree(work.parent, entries, threads > 1 ? kUnitsPerThread * threads : 1);
    work.threads = threads;
    work.units = 0;
    work.owner.assign(n, -1);
    for (const auto& mine : split.subtrees)
      for (const auto& [first, root] : mine)
        std::fill(work.owner.begin() + first, work.owner.begin() + root + 1, work.units++);
  }
  for (size_t first = 0; first < deltas.size(); first += kTermsPerSweep) {
    const int m = static_cast<int>(std::min<size_t>(kTermsPerSweep, deltas.size() - first));
    const std::ptrdiff_t failed = sweep(f, deltas.data() + first, m, work);
    if (failed >= 0) return failed;
  }
  return -1;
}

}  // namespace lapis::solver::detail
