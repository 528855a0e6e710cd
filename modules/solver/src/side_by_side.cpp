#include "lapis/solver/side_by_side.h"

#include <future>

#include "lapis/solver/blas_threads.h"

namespace lapis::solver {

void side_by_side(const std::function<void()>& main, const std::function<void()>& side) {
  const ScopedBlasThreads one_each(1);
  std::future<void> side_done = std::async(std::launch::async, side);
  try {
    main();
  } catch (...) {
    side_done.wait();  // main's error is the one to report; side must not outlive its data
    throw;
  }
  side_done.get();  // rethrows side's error
}

}  // namespace lapis::solver
