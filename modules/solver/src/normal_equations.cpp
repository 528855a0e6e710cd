#include "normal_equations.h"

#include <omp.h>

#include <algorithm>

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

// W A in rows (Gustavson): row r is Σ_s W(r, s) · row s of A. Eigen's product builds the
// column-major result and converts it, several times slower on E_R's metric.
RowMajor metric_times(const SparseMatrix& W, const RowMajor& A) {
  const RowMajor Wr = W;
  RowMajor Y(W.rows(), A.cols());
  std::vector<double> acc(static_cast<size_t>(A.cols()), 0.0);
  std::vector<char> touched(static_cast<size_t>(A.cols()), 0);
  std::vector<int> list;
  std::vector<int> outer(static_cast<size_t>(W.rows()) + 1, 0);
  std::vector<int> inner;
  std::vector<double> values;
  for (int r = 0; r < Wr.rows(); ++r) {
    for (RowMajor::InnerIterator w(Wr, r); w; ++w)
      for (RowMajor::InnerIterator a(A, w.col()); a; ++a) {
        const size_t k = static_cast<size_t>(a.col());
        if (!touched[k]) touched[k] = 1, list.push_back(a.col());
        acc[k] += w.value() * a.value();
      }
    std::sort(list.begin(), list.end());
    for (int k : list) {
      inner.push_back(k);
      values.push_back(acc[static_cast<size_t>(k)]);
      acc[static_cast<size_t>(k)] = 0, touched[static_cast<size_t>(k)] = 0;
    }
    list.clear();
    outer[static_cast<size_t>(r) + 1] = static_cast<int>(inner.size());
  }
  Y.resizeNonZeros(static_cast<Eigen::Index>(inner.size()));
  std::copy(outer.begin(), outer.end(), Y.outerIndexPtr());
  std::copy(inner.begin(), inner.end(), Y.innerIndexPtr());
  std::copy(values.begin(), values.end(), Y.valuePtr());
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

}  // namespace

NormalMatrices normal_matrices(const std::vector<WeightedBlock>& blocks, const std::vector<int>& free,
                               const std::vector<int>& fixed, int n) {
  // role[c] >= 0: free index; role[c] < 0: fixed index -role[c] - 1.
  std::vector<int> role(static_cast<size_t>(n), 0);
  for (size_t j = 0; j < free.size(); ++j) role[static_cast<size_t>(free[j])] = static_cast<int>(j);
  for (size_t j = 0; j < fixed.size(); ++j) role[static_cast<size_t>(fixed[j])] = -static_cast<int>(j) - 1;
  // Rows of each block's W_b A_b (CSR): column c of Aᵀ W A is Σ over the entries A(r, c) of
  // A(r, c) · row r of W A (W symmetric).
  std::vector<RowMajor> rows(blocks.size());
  for (size_t b = 0; b < blocks.size(); ++b) {
    rows[b] = *blocks[b].A;
    rows[b].makeCompressed();
    if (blocks[b].metric) rows[b] = metric_times(*blocks[b].metric, rows[b]);
  }
  const int nf = static_cast<int>(free.size());
  // Contiguous column ranges of about equal work, one per thread, so the runs concatenate in
  // column order. Work of column c ≈ Σ over its entries of the entry's row length.
  const int threads = std::max(1, std::min(omp_get_max_threads(), nf / 256 + 1));
  std::vector<double> work(static_cast<size_t>(nf) + 1, 0.0);
  for (int j = 0; j < nf; ++j) {
    double w = 0;
    for (size_t b = 0; b < blocks.size(); ++b)
      for (SparseMatrix::InnerIterator e(*blocks[b].A, free[static_cast<size_t>(j)]); e; ++e)
        w += rows[b].outerIndexPtr()[e.row() + 1] - rows[b].outerIndexPtr()[e.row()];
    work[static_cast<size_t>(j) + 1] = work[static_cast<size_t>(j)] + w + 1;
  }
  std::vector<int> begin(static_cast<size_t>(threads) + 1, nf);
  for (int t = 0; t < threads; ++t)
    begin[static_cast<size_t>(t)] = static_cast<int>(
        std::lower_bound(work.begin(), work.end(), work.back() * t / threads) - work.begin());
  begin[0] = 0;
  std::vector<ColumnRun> runs(static_cast<size_t>(threads));

#pragma omp parallel for num_threads(threads) schedule(static, 1)
  for (int t = 0; t < threads; ++t) {
    ColumnRun& run = runs[static_cast<size_t>(t)];
    Accumulator acc(n);
    for (int j = begin[static_cast<size_t>(t)]; j < std::max(begin[static_cast<size_t>(t)], begin[static_cast<size_t>(t) + 1]); ++j) {
      const int c = free[static_cast<size_t>(j)];
      for (size_t b = 0; b < blocks.size(); ++b) {
        const RowMajor& R = rows[b];
        const int* row_start = R.outerIndexPtr();
        const int* cols = R.innerIndexPtr();
        const double* vals = R.valuePtr();
        for (SparseMatrix::InnerIterator e(*blocks[b].A, c); e; ++e) {
          const double a = blocks[b].weight * e.value();
          for (int p = row_start[e.row()]; p < row_start[e.row() + 1]; ++p) {
            const int k = cols[p];
            if (!acc.touched[static_cast<size_t>(k)]) {
              acc.touched[static_cast<size_t>(k)] = 1;
              const int r = role[static_cast<size_t>(k)];
              (r >= 0 ? acc.free_list : acc.fixed_list).push_back(r >= 0 ? r : -r - 1);
            }
            acc.value[static_cast<size_t>(k)] += a * vals[p];
          }
        }
      }
      // Sorted rows, values read back and the accumulator cleared.
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
  }
  // The free-fixed block as built is (fixed by free)ᵀ laid out per free column: column j holds
  // the fixed unknowns coupled to free unknown j, i.e. row j of free_fixed. Build it as
  // #fixed by #free and transpose.
  NormalMatrices out;
  // w_b A_b(:, free)ᵀ W_b = (w_b W_b A_b(:, free))ᵀ: column r is row r of W_b A_b, free unknowns
  // renumbered (ascending, as free is).
  for (size_t b = 0; b < blocks.size(); ++b) {
    const RowMajor& R = rows[b];
    SparseMatrix T(nf, static_cast<int>(R.rows()));
    T.reserve(R.nonZeros());
    for (int r = 0; r < R.rows(); ++r) {
      T.startVec(r);
      for (RowMajor::InnerIterator e(R, r); e; ++e)
        if (role[static_cast<size_t>(e.col())] >= 0)
          T.insertBack(role[static_cast<size_t>(e.col())], r) = blocks[b].weight * e.value();
    }
    T.finalize();
    out.weighted_free_t.push_back(std::move(T));
  }
  out.free_free = assemble(nf, nf, runs, false);
  const SparseMatrix fixed_free = assemble(static_cast<int>(fixed.size()), nf, runs, true);
  out.free_fixed = fixed_free.transpose();
  return out;
}

}  // namespace lapis::solver::detail
