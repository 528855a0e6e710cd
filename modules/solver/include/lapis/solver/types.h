// Types shared by the solver layer's public API: Eigen only, CHOLMOD never leaks out.
#pragma once

#include <cstdint>
#include <string>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "lapis/core/error.h"

namespace lapis::solver {

// Column-major sparse matrix with int indices: what Eigen's sparse solvers and CHOLMOD's
// int interface both take without copying indices.
using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
using DenseMatrix = Eigen::MatrixXd;

// Which implementation factorizes. CHOLMOD is the product; Eigen's SimplicialLDLT exists to
// cross-check it in tests and is never substituted silently.
enum class Backend { Cholmod, Eigen };

// CHOLMOD's two factor kinds: supernodal LL' (fast factorization through BLAS) and
// simplicial LDL' (the kind cholmod_updown modifies).
enum class FactorKind { Supernodal, Simplicial };

const char* to_string(Backend b);
const char* to_string(FactorKind k);

// What a factorization cost and produced.
struct FactorReport {
  Backend backend = Backend::Cholmod;
  FactorKind kind = FactorKind::Supernodal;
  int n = 0;                // rows of A
  std::int64_t nnz_A = 0;   // non-zeros of A (both triangles)
  std::int64_t nnz_L = 0;   // non-zeros of the factor L
  double flops = 0;         // floating-point operations of the numeric factorization
  std::string ordering;     // fill-reducing ordering the analysis chose (AMD, METIS, ...)
  double analyze_ms = 0;    // symbolic analysis
  double factorize_ms = 0;  // last numeric factorization
  double solve_ms = 0;      // last solve
};

}  // namespace lapis::solver
