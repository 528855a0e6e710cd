#include "normal_equations.h"

#include <omp.h>

#include <algorithm>
#include <cstdint>

namespace lapis::solver::detail {
namespace {

using RowMajor = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;

// One thread's output for a contiguous range of columns: entries appended column by column.
struct ColumnRun {
  std::vector<int> count_ff, count_fx;  // per column of the range
  std::vector<int> rows_ff, rows_fx;
  std::vector<double> values_ff, values_fx;
};

// Dense accumulator over the n unknowns with the list of touched ones (Gustavson's SPA).
struct Accumulator {
  std::vector<double> value;
  std::vector<char> touched;
  std::vector<int> free_list, fixed_list;  // role indices touched, unsorted
  explicit Accumulator(int n) : value(static_cast<size_t>(n), 0.0), touched(static_cast<size_t>(n), 0) {}
};

// Pieces of work per thread. The pieces are taken by whichever thread is free (dynamic
// schedule) and written to their own runs, concatenated in order afterwards: in mesh_deform's
// set-up a second factorization holds one of the two cores while this runs, and with one
// contiguous half per thread the half that waited for that core set the time. Eq. 2.8's
// normal matrix of a 50K-vertex merge: median 373 → 262 ms over eight alternating runs.
constexpr int kPiecesPerThread = 16;

// W A in rows (Gustavson): row r is Σ_s W(r, s) · row s of A, W symmetric so its column r
// (read in place) is its row r. Eigen's product builds the column-major result and converts
// it, several times slower on E_R's metric. Rows in contiguous pieces (see above).
RowMajor metric_times(const SparseMatrix& W, const RowMajor& A) {
  struct Run {
    std::vector<int> row_end, inner;
    std::vector<double> values;
  };
  const int m = static_cast<int>(W.cols());
  const int threads = std::max(1, std::min(omp_get_max_threads(), m / 4096 + 1));
  const int pieces = threads == 1 ? 1 : threads * kPiecesPerThread;
  std::vector<Run> runs(static_cast<size_t>(pieces));
#pragma omp parallel num_threads(threads)
  {
    std::vector<double> acc(static_cast<size_t>(A.cols()), 0.0);
    std::vector<char> touched(static_cast<size_t>(A.cols()), 0);
    std::vector<int> list;
#pragma omp for schedule(dynamic, 1)
    for (int piece = 0; piece < pieces; ++piece) {
      Run& out = runs[static_cast<size_t>(piece)];
      const int first = static_cast<int>(static_cast<std::int64_t>(m) * piece / pieces);
      const int last = static_cast<int>(static_cast<std::int64_t>(m) * (piece + 1) / pieces);
      out.row_end.reserve(static_cast<size_t>(last - first));
      for (int r = first; r < last; ++r) {
        for (SparseMatrix::InnerIterator w(W, r); w; ++w)
          for (RowMajor::InnerIterator a(A, w.row()); a; ++a) {
            const size_t k = static_cast<size_t>(a.col());
            if (!touched[k]) touched[k] = 1, list.push_back(a.col());
            acc[k] += w.value() * a.value();
          }
        std::sort(list.begin(), list.end());
        for (int k : list) {
          out.inner.push_back(k);
          out.values.push_back(acc[static_cast<size_t>(k)]);
          acc[static_cast<size_t>(k)] = 0, touched[static_cast<size_t>(k)] = 0;
        }
        list.clear();
        out.row_end.push_back(static_cast<int>(out.inner.size()));
      }
    }
  }
  size_t total = 0;
  for (const Run& r : runs) total += r.inner.size();
  RowMajor Y(W.rows(), A.cols());
  Y.resizeNonZeros(static_cast<Eigen::Index>(total));
  int* outer = Y.outerIndexPtr();
  int row = 0, at = 0;
  outer[0] = 0;
  for (const Run& r : runs) {
    std::copy(r.inner.begin(), r.inner.end(), Y.innerIndexPtr() + at);
    std::copy(r.values.begin(), r.values.end(), Y.valuePtr() + at);
    for (int end : r.row_end) outer[++row] = at + end;
    at += static_cast<int>(r.inner.size());
  }
  return Y;
}

SparseMatrix assemble(int rows, int cols, const std::vector<ColumnRun>& runs, bool fixed_part) {
  SparseMatrix M(rows, cols);
  size_t total = 0;
  for (const auto& r : runs) total += (fixed_part ? r.rows_fx : r.rows_ff).size();
  M.resizeNonZeros(static_cast<Eigen::Index>(total));
  int* outer = M.outerIndexPtr();
  int* inner = M.innerIndexPtr();
  double* values = M.valuePtr();
  int column = 0, at = 0;
  outer[0] = 0;
  for (const auto& r : runs) {
    const auto& counts = fixed_part ? r.count_fx : r.count_ff;
    const auto& rr = fixed_part ? r.rows_fx : r.rows_ff;
    const auto& vv = fixed_part ? r.values_fx : r.values_ff;
    std::copy(rr.begin(), rr.end(), inner + at);
    std::copy(vv.begin(), vv.end(), values + at);
    for (int c : counts) {
      at += c;
      outer[++column] = at;
    }
  }
  return M;
}

// Rows of each block's W_b A_b (CSR): column c of Aᵀ W A is Σ over the entries A(r, c) of
// A(r, c) · row r of W A (W symmetric).
std::vector<RowMajor> weighted_rows(const std::vector<WeightedBlock>& blocks) {
  std::vector<RowMajor> rows(blocks.size());
  for (size_t b = 0; b < blocks.size(); ++b) {
    rows[b] = *blocks[b].A;
    rows[b].makeCompressed();
    if (blocks[b].metric) {
      // Swapped in, not assigned: Eigen 3.4's SparseMatrix has no move, and `=` from a named
      // result copies it (fresh pages, each faulted in; see page_populate.h).
      RowMajor weighted = metric_times(*blocks[b].metric, rows[b]);
      rows[b].swap(weighted);
    }
  }
  return rows;
}

// Contiguous column pieces of about equal work (see kPiecesPerThread), so the runs concatenate
// in column order: piece t holds free columns [begin[t], begin[t + 1]). Work of column c ≈ Σ
// over its entries of the entry's row length.
std::vector<int> column_pieces(const std::vector<WeightedBlock>& blocks, const std::vector<RowMajor>& rows,
                               const std::vector<int>& free, int pieces) {
  const int nf = static_cast<int>(free.size());
  std::vector<double> work(static_cast<size_t>(nf) + 1, 0.0);
  for (int j = 0; j < nf; ++j) {
    double w = 0;
    for (size_t b = 0; b < blocks.size(); ++b)
      for (SparseMatrix::InnerIterator e(*blocks[b].A, free[static_cast<size_t>(j)]); e; ++e)
        w += rows[b].outerIndexPtr()[e.row() + 1] - rows[b].outerIndexPtr()[e.row()];
    work[static_cast<size_t>(j) + 1] = work[static_cast<size_t>(j)] + w + 1;
  }
  std::vector<int> begin(static_cast<size_t>(pieces) + 1, nf);
  for (int t = 0; t < pieces; ++t)
    begin[static_cast<size_t>(t)] =
        static_cast<int>(std::lower_bound(work.begin(), work.end(), work.back() * t / pieces) - work.begin());
  begin[0] = 0;
  return begin;
}

// Column j (unknown c) of Aᵀ W A into the accumulator, lower triangle only. role[k] >= 0: free
// index; role[k] < 0: fixed index -role[k] - 1.
void accumulate_column(int j, int c, const std::vector<WeightedBlock>& blocks, const std::vector<RowMajor>& rows,
                       const std::vector<int>& role, Accumulator& acc) {
  for (size_t b = 0; b < blocks.size(); ++b) {
    const int* row_start = rows[b].outerIndexPtr();
    const int* cols = rows[b].innerIndexPtr();
    const double* vals = rows[b].valuePtr();
    for (SparseMatrix::InnerIterator e(*blocks[b].A, c); e; ++e) {
      const double a = blocks[b].weight * e.value();
      for (int p = row_start[e.row()]; p < row_start[e.row() + 1]; ++p) {
        const int k = cols[p];
        const int r = role[static_cast<size_t>(k)];
        if (r >= 0 && r < j) continue;  // the upper triangle: nothing reads it
        if (!acc.touched[static_cast<size_t>(k)]) {
          acc.touched[static_cast<size_t>(k)] = 1;
          (r >= 0 ? acc.free_list : acc.fixed_list).push_back(r >= 0 ? r : -r - 1);
        }
        acc.value[static_cast<size_t>(k)] += a * vals[p];
      }
    }
  }
}

// The accumulated column appended to the run, rows sorted; the accumulator cleared.
void flush_column(Accumulator& acc, const std::vector<int>& free, const std::vector<int>& fixed, ColumnRun& run) {
  std::sort(acc.free_list.begin(), acc.free_list.end());
  std::sort(acc.fixed_list.begin(), acc.fixed_list.end());
  for (int r : acc.free_list) {
    const size_t k = static_cast<size_t>(free[static_cast<size_t>(r)]);
    run.rows_ff.push_back(r);
    run.values_ff.push_back(acc.value[k]);
    acc.value[k] = 0, acc.touched[k] = 0;
  }
  for (int r : acc.fixed_list) {
    const size_t k = static_cast<size_t>(fixed[static_cast<size_t>(r)]);
    run.rows_fx.push_back(r);
    run.values_fx.push_back(acc.value[k]);
    acc.value[k] = 0, acc.touched[k] = 0;
  }
  run.count_ff.push_back(static_cast<int>(acc.free_list.size()));
  run.count_fx.push_back(static_cast<int>(acc.fixed_list.size()));
  acc.free_list.clear();
  acc.fixed_list.clear();
}

}  // namespace

NormalMatrices normal_matrices(const std::vector<WeightedBlock>& blocks, const std::vector<int>& free,
                               const std::vector<int>& fixed, int n) {
  std::vector<int> role(static_cast<size_t>(n), 0);  // see accumulate_column
  for (size_t j = 0; j < free.size(); ++j) role[static_cast<size_t>(free[j])] = static_cast<int>(j);
  for (size_t j = 0; j < fixed.size(); ++j) role[static_cast<size_t>(fixed[j])] = -static_cast<int>(j) - 1;
  const std::vector<RowMajor> rows = weighted_rows(blocks);
  const int nf = static_cast<int>(free.size());
  const int threads = std::max(1, std::min(omp_get_max_threads(), nf / 256 + 1));
  const int pieces = threads == 1 ? 1 : threads * kPiecesPerThread;
  const std::vector<int> begin = column_pieces(blocks, rows, free, pieces);
  std::vector<ColumnRun> runs(static_cast<size_t>(pieces));
#pragma omp parallel num_threads(threads)
  {
    Accumulator acc(n);
#pragma omp for schedule(dynamic, 1)
    for (int t = 0; t < pieces; ++t) {
      const int first = begin[static_cast<size_t>(t)], last = std::max(first, begin[static_cast<size_t>(t) + 1]);
      for (int j = first; j < last; ++j) {
        accumulate_column(j, free[static_cast<size_t>(j)], blocks, rows, role, acc);
        flush_column(acc, free, fixed, runs[static_cast<size_t>(t)]);
      }
    }
  }
  // The free-fixed block as built is (fixed by free)ᵀ laid out per free column: column j holds
  // the fixed unknowns coupled to free unknown j, i.e. row j of free_fixed. Build it as
  // #fixed by #free and transpose.
  NormalMatrices out;
  SparseMatrix free_free = assemble(nf, nf, runs, false);
  out.free_free.swap(free_free);  // not `=`, which would copy (see above)
  const SparseMatrix fixed_free = assemble(static_cast<int>(fixed.size()), nf, runs, true);
  out.free_fixed = fixed_free.transpose();
  return out;
}

}  // namespace lapis::solver::detail
