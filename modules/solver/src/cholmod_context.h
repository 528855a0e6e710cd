// Private CHOLMOD plumbing: one cholmod_common per solver object (so independent objects
// can run on different threads), CHOLMOD's error handler routed into lapis exceptions, and
// zero-copy views of Eigen matrices. Nothing here is visible outside modules/solver/src.
#pragma once

#include <cholmod.h>

#include <mutex>
#include <string>

#include "lapis/core/error.h"
#include "lapis/solver/types.h"

namespace lapis::solver::detail {

class CholmodContext {
 public:
  CholmodContext();
  ~CholmodContext();
  CholmodContext(const CholmodContext&) = delete;
  CholmodContext& operator=(const CholmodContext&) = delete;

  cholmod_common* get() { return &common_; }
  const cholmod_common* get() const { return &common_; }

  // Throws SolverFailure (or ResourceLimit when out of memory) if the last call failed;
  // `function` names the Lapis function for the message. Warnings (not positive definite)
  // are left to the caller, which knows the column.
  void check(const char* function, const char* cholmod_call) const;

 private:
  cholmod_common common_{};
};

// Held around every CHOLMOD call that may run METIS (cholmod_bisect; cholmod_analyze when it
// chooses the ordering). METIS keeps its random generator (GKlib's Mersenne twister) in
// process-wide statics and reseeds it at each call, with the global index as the loop
// variable: two calls at once give orderings that depend on the timing, and the seeding loop
// of one can run the other's index past its array. mesh_deform orders its two systems on
// two threads; at 200K vertices both reach METIS.
std::mutex& metis_mutex();

// A cholmod_sparse header over A's arrays; A must be compressed and outlive the view.
// stype = -1: CHOLMOD reads the lower triangle only.
cholmod_sparse sparse_view(const SparseMatrix& A, int stype);
// A cholmod_dense header over B's column-major storage.
cholmod_dense dense_view(const DenseMatrix& B);
// Copies a CHOLMOD dense result into an Eigen matrix.
DenseMatrix to_eigen(const cholmod_dense& X);

// "AMD", "METIS", ... for common->method[selected].ordering.
const char* ordering_name(int ordering);

// The column of the original matrix at which a factorization broke (L->minor, un-permuted).
std::ptrdiff_t failed_column(const cholmod_factor* L);

}  // namespace lapis::solver::detail
