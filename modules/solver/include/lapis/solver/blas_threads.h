// The BLAS library's own thread count, for code that runs two factorizations side by side.
// CHOLMOD's supernodal factorization calls BLAS, and OpenBLAS (pthread build) runs one thread
// per core that busy-waits with sched_yield between calls. Two factorizations at once, each
// with its BLAS threads, then fight over the cores: a 16K-vertex merge (both implicit Laplacian
// systems factorized together) took 1.2 s with OpenBLAS' default and 0.85 s with one BLAS
// thread each. One factorization alone gains under 10% from a second BLAS thread.
#pragma once

namespace lapis::solver {

// Sets the BLAS thread count for the guard's lifetime and restores it after. OpenBLAS is
// found at run time (openblas_set_num_threads); with another BLAS it does nothing. The count
// is process-wide: BLAS calls on other threads meanwhile run with it too. Guards may overlap
// (on several threads too); the count before the first is restored when the last ends.
class ScopedBlasThreads {
 public:
  explicit ScopedBlasThreads(int threads);
  ~ScopedBlasThreads();
  ScopedBlasThreads(const ScopedBlasThreads&) = delete;
  ScopedBlasThreads& operator=(const ScopedBlasThreads&) = delete;

  // The BLAS is OpenBLAS and its count can be set.
  static bool available();
  // OpenBLAS' thread count now, or 0 when not available.
  static int current();

 private:
  bool active_ = false;
};

}  // namespace lapis::solver
