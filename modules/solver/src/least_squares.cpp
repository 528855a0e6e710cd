#include "lapis/solver/least_squares.h"

#include <algorithm>
#include <deque>

#include "checks.h"
#include "lapis/core/format.h"
#include "lapis/core/parallel_for.h"
#include "lapis/solver/ordering.h"
#include "normal_equations.h"

namespace lapis::solver {

struct LeastSquares::Impl {
  struct Block {
    SparseMatrix A;
    double weight;
    std::string name;
    SparseMatrix metric;  // empty: the identity
    bool has_metric = false;
  };
  int n = 0;
  // A deque: blocks never move once added. Eigen 3.4's sparse matrices have no move at all, so
  // a vector copied every block on each growth (~50 MB at a 50K-vertex merge's E_R).
  std::deque<Block> blocks;
  std::vector<int> fixed, free;
  SparseMatrix skeleton;  // empty: CHOLMOD orders
  Cholesky chol;
  SparseMatrix free_fixed;  // Σ w_b A_b(:, free)' A_b(:, fixed)
  bool precomputed = false;

  explicit Impl(CholeskyOptions o) : chol(o) {}

  // Appends a checked block, swapping A and metric (if any) into place: Eigen 3.4's
  // SparseMatrix has no move, and a copy of E_R's block at a 50K-vertex merge is ~23 MB of
  // fresh pages (page_populate.h says what those cost).
  int append(SparseMatrix& A, double weight, std::string name, SparseMatrix* metric) {
    Block& block = blocks.emplace_back();
    block.A.swap(A);
    block.weight = weight;
    block.name = std::move(name);
    if (metric) {
      block.metric.swap(*metric);
      block.has_metric = true;
    }
    precomputed = false;
    return static_cast<int>(blocks.size()) - 1;
  }

  const Block& block(int id, const char* fn) const {
    if (id < 0 || id >= static_cast<int>(blocks.size()))
      throw InvalidArgument(std::string(fn) + ": block " + std::to_string(id) + " out of range [0, " +
                            std::to_string(blocks.size()) + ")");
    return blocks[static_cast<size_t>(id)];
  }
};

LeastSquares::LeastSquares(int n, CholeskyOptions options) : impl_(std::make_unique<Impl>(options)) {
  if (n <= 0)
    throw InvalidArgument("solver::LeastSquares::LeastSquares(): " + std::to_string(n) +
                          " unknowns, expected at least one");
  impl_->n = n;
  set_fixed({});
}
LeastSquares::~LeastSquares() = default;
LeastSquares::LeastSquares(LeastSquares&&) noexcept = default;
LeastSquares& LeastSquares::operator=(LeastSquares&&) noexcept = default;

namespace {

void check_block(const SparseMatrix& A, double weight, int n, const char* fn) {
  if (A.cols() != n)
    throw InvalidArgument(std::string(fn) + ": block is " + detail::dims(A.rows(), A.cols()) + ", expected " +
                          std::to_string(n) + " columns");
  if (!(std::isfinite(weight) && weight > 0))
    throw InvalidArgument(std::string(fn) + ": weight " + format_number(weight) + " is not finite and > 0");
  detail::require_finite(A, fn);
}

}  // namespace

int LeastSquares::add_block(SparseMatrix A, double weight, std::string name) {
  check_block(A, weight, impl_->n, "solver::LeastSquares::add_block()");
  return impl_->append(A, weight, std::move(name), nullptr);
}

int LeastSquares::add_block(SparseMatrix A, double weight, std::string name, SparseMatrix metric) {
  constexpr const char* fn = "solver::LeastSquares::add_block()";
  check_block(A, weight, impl_->n, fn);
  if (metric.rows() != A.rows() || metric.cols() != A.rows())
    throw InvalidArgument(std::string(fn) + ": metric is " + detail::dims(metric.rows(), metric.cols()) +
                          ", expected " + detail::dims(A.rows(), A.rows()) + " (the block's rows)");
  detail::require_finite(metric, fn);
  return impl_->append(A, weight, std::move(name), &metric);
}

const SparseMatrix& LeastSquares::block_matrix(int id) const {
  return impl_->block(id, "solver::LeastSquares::block_matrix()").A;
}

const SparseMatrix& LeastSquares::block_metric(int id) const {
  return impl_->block(id, "solver::LeastSquares::block_metric()").metric;
}

void LeastSquares::set_fixed(std::vector<int> indices) {
  constexpr const char* fn = "solver::LeastSquares::set_fixed()";
  const int n = impl_->n;
  std::vector<char> is_fixed(static_cast<size_t>(n), 0);
  for (int i : indices) {
    if (i < 0 || i >= n)
      throw InvalidArgument(std::string(fn) + ": index " + std::to_string(i) + " out of range [0, " +
                            std::to_string(n) + ")");
    if (is_fixed[static_cast<size_t>(i)])
      throw InvalidArgument(std::string(fn) + ": index " + std::to_string(i) + " given twice");
    is_fixed[static_cast<size_t>(i)] = 1;
  }
  impl_->fixed = std::move(indices);
  impl_->free.clear();
  for (int i = 0; i < n; ++i)
    if (!is_fixed[static_cast<size_t>(i)]) impl_->free.push_back(i);
  impl_->precomputed = false;
}

void LeastSquares::set_ordering_skeleton(SparseMatrix skeleton) {
  constexpr const char* fn = "solver::LeastSquares::set_ordering_skeleton()";
  const int n = impl_->n;
  if (skeleton.size() > 0 && (skeleton.rows() != n || skeleton.cols() != n))
    throw InvalidArgument(std::string(fn) + ": skeleton is " + detail::dims(skeleton.rows(), skeleton.cols()) +
                          ", expected " + detail::dims(n, n));
  skeleton.makeCompressed();
  impl_->skeleton.swap(skeleton);  // std::move would copy (Eigen 3.4's SparseMatrix has no move)
  impl_->precomputed = false;
}

namespace {

// S(free, free): the skeleton's pattern among the free unknowns, renumbered.
SparseMatrix restrict_to(const SparseMatrix& S, const std::vector<int>& free, int n) {
  std::vector<int> index(static_cast<size_t>(n), -1);
  for (size_t j = 0; j < free.size(); ++j) index[static_cast<size_t>(free[j])] = static_cast<int>(j);
  const int nf = static_cast<int>(free.size());
  SparseMatrix R(nf, nf);
  R.reserve(S.nonZeros());
  for (int j = 0; j < nf; ++j) {
    R.startVec(j);
    for (SparseMatrix::InnerIterator e(S, free[static_cast<size_t>(j)]); e; ++e)
      if (const int i = index[static_cast<size_t>(e.row())]; i >= 0) R.insertBackByOuterInnerUnordered(j, i) = 1.0;
  }
  R.finalize();
  return R;
}

}  // namespace

void LeastSquares::precompute() {
  constexpr const char* fn = "solver::LeastSquares::precompute()";
  Impl& m = *impl_;
  if (m.blocks.empty()) throw InvalidArgument(std::string(fn) + ": no blocks added");
  if (m.free.empty()) throw InvalidArgument(std::string(fn) + ": every unknown is fixed; nothing to solve");
  std::vector<detail::WeightedBlock> blocks;
  for (const auto& b : m.blocks) blocks.push_back({&b.A, b.weight, b.has_metric ? &b.metric : nullptr});
  detail::NormalMatrices normal = detail::normal_matrices(blocks, m.free, m.fixed, m.n);
  const SparseMatrix& N = normal.free_free;
  m.free_fixed.swap(normal.free_fixed);  // std::move would copy: Eigen 3.4's SparseMatrix has no move
  try {
    if (m.skeleton.size() > 0)
      m.chol.analyze(N, skeleton_nested_dissection(N, restrict_to(m.skeleton, m.free, m.n)));
    else
      m.chol.analyze(N);
    m.chol.factorize(N);
  } catch (const NotPositiveDefinite& e) {
    throw NotPositiveDefinite(std::string(fn) +
                                  ": the free unknowns are not determined by the blocks "
                                  "(normal matrix not positive definite): " +
                                  e.what(),
                              e.column() >= 0 ? m.free[static_cast<size_t>(e.column())] : -1);
  }
  m.precomputed = true;
}

bool LeastSquares::precomputed() const { return impl_->precomputed; }

namespace {

// sum = Σ_e A(e, c) R(e, :) over the entries of column c of A, R row-major with K columns
// (K = 0: k, known at run time only).
template <int K>
void gather_column(const SparseMatrix& A, Eigen::Index c, const double* R, Eigen::Index k, double* sum) {
  const Eigen::Index width = K > 0 ? K : k;
  std::fill(sum, sum + width, 0.0);
  for (SparseMatrix::InnerIterator e(A, c); e; ++e) {
    const double* r = R + e.row() * width;
    for (Eigen::Index i = 0; i < width; ++i) sum[i] += e.value() * r[i];
  }
}

// b.row(j) += weight (Aᵀ R).row(free[j]) for every free unknown j, in chunks over
// core::parallel_for. Eigen's product of the row-major Aᵀ would open an OpenMP team every
// frame (over 20,000 entries), whose barrier waits on a descheduled member. R is copied to
// row-major first: each row a column of A gathers is then one cache line, not one per
// right-hand side, and only the free columns are formed.
void add_transpose_times(const SparseMatrix& A, double weight, const DenseMatrix& R, const std::vector<int>& free,
                         DenseMatrix& b) {
  const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rows = R;
  const Eigen::Index k = R.cols();
  core::parallel_for(0, static_cast<std::ptrdiff_t>(free.size()), 2048, [&](std::ptrdiff_t lo, std::ptrdiff_t hi) {
    Eigen::VectorXd sum(k);
    for (std::ptrdiff_t j = lo; j < hi; ++j) {
      const Eigen::Index c = free[static_cast<size_t>(j)];
      if (k == 3)  // the usual x, y, z: a width the compiler unrolls
        gather_column<3>(A, c, rows.data(), k, sum.data());
      else
        gather_column<0>(A, c, rows.data(), k, sum.data());
      b.row(j) += weight * sum.transpose();
    }
  });
}

}  // namespace

DenseMatrix LeastSquares::normal_rhs(const std::vector<DenseMatrix>& rhs, const DenseMatrix& fixed_values) const {
  constexpr const char* fn = "solver::LeastSquares::solve()";
  const Impl& m = *impl_;
  if (!m.precomputed) throw InvalidArgument(std::string(fn) + ": call precompute() first");
  if (rhs.size() != m.blocks.size())
    throw InvalidArgument(std::string(fn) + ": " + std::to_string(rhs.size()) +
                          " right-hand sides, expected one per block (" + std::to_string(m.blocks.size()) + ")");
  Eigen::Index k = -1;
  for (const auto& r : rhs)
    if (r.size() > 0) k = r.cols();
  if (k < 0) k = fixed_values.size() > 0 ? fixed_values.cols() : 1;
  DenseMatrix b = DenseMatrix::Zero(static_cast<Eigen::Index>(m.free.size()), k);
  for (size_t i = 0; i < rhs.size(); ++i) {
    if (rhs[i].size() == 0) continue;
    const auto rows = m.blocks[i].A.rows();
    if (rhs[i].rows() != rows || rhs[i].cols() != k)
      throw InvalidArgument(std::string(fn) + ": right-hand side of block " + std::to_string(i) +
                            (m.blocks[i].name.empty() ? "" : " ('" + m.blocks[i].name + "')") + " is " +
                            detail::dims(rhs[i].rows(), rhs[i].cols()) + ", expected " + detail::dims(rows, k));
    if (!rhs[i].allFinite())
      throw InvalidArgument(std::string(fn) + ": right-hand side of block " + std::to_string(i) +
                            " has a non-finite entry");
    // w_b A_b(:, free)ᵀ W_b r_b, formed per solve: W_b r_b and A_bᵀ of it cost fewer
    // multiply-adds than a precomputed (W_b A_b(:, free))ᵀ has entries (millions at a 50K-vertex
    // E_R, whose assembly was a serial pass of the setup).
    const Impl::Block& B = m.blocks[i];
    if (B.has_metric)
      add_transpose_times(B.A, B.weight, DenseMatrix(B.metric * rhs[i]), m.free, b);
    else
      add_transpose_times(B.A, B.weight, rhs[i], m.free, b);
  }
  if (!m.fixed.empty()) {
    if (fixed_values.rows() != static_cast<Eigen::Index>(m.fixed.size()) || fixed_values.cols() != k)
      throw InvalidArgument(std::string(fn) + ": fixed values are " +
                            detail::dims(fixed_values.rows(), fixed_values.cols()) + ", expected " +
                            detail::dims(static_cast<Eigen::Index>(m.fixed.size()), k));
    if (!fixed_values.allFinite()) throw InvalidArgument(std::string(fn) + ": fixed values have a non-finite entry");
    b -= m.free_fixed * fixed_values;
  }
  return b;
}

DenseMatrix LeastSquares::solve(const std::vector<DenseMatrix>& rhs, const DenseMatrix& fixed_values) const {
  const Impl& m = *impl_;
  const DenseMatrix b = normal_rhs(rhs, fixed_values);
  const DenseMatrix x_free = m.chol.solve(b);
  DenseMatrix x(m.n, b.cols());
  for (size_t j = 0; j < m.free.size(); ++j) x.row(m.free[j]) = x_free.row(static_cast<Eigen::Index>(j));
  for (size_t j = 0; j < m.fixed.size(); ++j) x.row(m.fixed[j]) = fixed_values.row(static_cast<Eigen::Index>(j));
  return x;
}

DenseMatrix LeastSquares::solve(const std::vector<DenseMatrix>& rhs, const DenseMatrix& fixed_values,
                                int refinement_steps) const {
  const Impl& m = *impl_;
  DenseMatrix x = solve(rhs, fixed_values);
  if (refinement_steps <= 0) return x;
  const DenseMatrix no_fixed = DenseMatrix::Zero(fixed_values.rows(), x.cols());
  for (int step = 0; step < refinement_steps; ++step) {
    // Each block's residual r_b − A_b x, formed from the rows themselves rather than through
    // the normal matrix: its rounding is cond(A), not cond(A)², times the unit roundoff.
    std::vector<DenseMatrix> residual(m.blocks.size());
    for (size_t i = 0; i < m.blocks.size(); ++i) {
      residual[i] = -(m.blocks[i].A * x);
      if (rhs[i].size() > 0) residual[i] += rhs[i];
    }
    const DenseMatrix dx = m.chol.solve(normal_rhs(residual, no_fixed));
    for (size_t j = 0; j < m.free.size(); ++j) x.row(m.free[j]) += dx.row(static_cast<Eigen::Index>(j));
  }
  return x;
}

int LeastSquares::unknowns() const { return impl_->n; }
int LeastSquares::num_blocks() const { return static_cast<int>(impl_->blocks.size()); }
const std::vector<int>& LeastSquares::fixed() const { return impl_->fixed; }
const std::vector<int>& LeastSquares::free() const { return impl_->free; }
const Cholesky& LeastSquares::factor() const { return impl_->chol; }

}  // namespace lapis::solver
