#include "cholmod_context.h"

#include <cstring>

namespace lapis::solver::detail {
namespace {

// CHOLMOD's error handler carries no user pointer; each thread records its own last message,
// which the context that made the failing call reads right after it.
thread_local std::string last_cholmod_message;

void record_error(int status, const char* file, int line, const char* message) {
  last_cholmod_message = std::string(message ? message : "unknown error") + " (status " + std::to_string(status) +
                         ", " + (file ? file : "?") + ":" + std::to_string(line) + ")";
}

}  // namespace

CholmodContext::CholmodContext() {
  cholmod_start(&common_);
  common_.print = 0;  // never print on our own; errors become exceptions
  common_.error_handler = record_error;
}

CholmodContext::~CholmodContext() { cholmod_finish(&common_); }

void CholmodContext::check(const char* function, const char* cholmod_call) const {
  const int status = common_.status;
  if (status >= CHOLMOD_OK) return;  // OK, or a warning the caller interprets
  std::string what = std::string(function) + ": " + cholmod_call + " failed: " +
                     (last_cholmod_message.empty() ? "status " + std::to_string(status) : last_cholmod_message);
  last_cholmod_message.clear();
  if (status == CHOLMOD_OUT_OF_MEMORY || status == CHOLMOD_TOO_LARGE) throw ResourceLimit(what);
  throw SolverFailure(what);
}

cholmod_sparse sparse_view(const SparseMatrix& A, int stype) {
  cholmod_sparse s{};
  s.nrow = static_cast<size_t>(A.rows());
  s.ncol = static_cast<size_t>(A.cols());
  s.nzmax = static_cast<size_t>(A.nonZeros());
  s.p = const_cast<int*>(A.outerIndexPtr());
  s.i = const_cast<int*>(A.innerIndexPtr());
  s.nz = nullptr;
  s.x = const_cast<double*>(A.valuePtr());
  s.z = nullptr;
  s.stype = stype;
  s.itype = CHOLMOD_INT;
  s.xtype = CHOLMOD_REAL;
  s.dtype = CHOLMOD_DOUBLE;
  s.sorted = 1;
  s.packed = 1;
  return s;
}

cholmod_dense dense_view(const DenseMatrix& B) {
  cholmod_dense d{};
  d.nrow = static_cast<size_t>(B.rows());
  d.ncol = static_cast<size_t>(B.cols());
  d.nzmax = d.nrow * d.ncol;
  d.d = d.nrow;
  d.x = const_cast<double*>(B.data());
  d.z = nullptr;
  d.xtype = CHOLMOD_REAL;
  d.dtype = CHOLMOD_DOUBLE;
  return d;
}

DenseMatrix to_eigen(const cholmod_dense& X) {
  DenseMatrix out(static_cast<Eigen::Index>(X.nrow), static_cast<Eigen::Index>(X.ncol));
  const double* x = static_cast<const double*>(X.x);
  for (size_t j = 0; j < X.ncol; ++j)
    std::memcpy(out.col(static_cast<Eigen::Index>(j)).data(), x + j * X.d, X.nrow * sizeof(double));
  return out;
}

const char* ordering_name(int ordering) {
  switch (ordering) {
    case CHOLMOD_NATURAL:
      return "natural";
    case CHOLMOD_GIVEN:
      return "given";
    case CHOLMOD_AMD:
      return "AMD";
    case CHOLMOD_METIS:
      return "METIS";
    case CHOLMOD_NESDIS:
      return "NESDIS";
    case CHOLMOD_COLAMD:
      return "COLAMD";
    case CHOLMOD_POSTORDERED:
      return "postordered";
    default:
      return "unknown";
  }
}

std::ptrdiff_t failed_column(const cholmod_factor* L) {
  const auto minor = static_cast<std::ptrdiff_t>(L->minor);
  if (minor < 0 || static_cast<size_t>(minor) >= L->n) return -1;
  const int* perm = static_cast<const int*>(L->Perm);
  return perm ? perm[minor] : minor;
}

std::mutex& metis_mutex() {
  static std::mutex m;
  return m;
}

}  // namespace lapis::solver::detail
