// parallel_for runs every index once, sums the same whichever thread ran what, passes
// exceptions on, and never waits for workers that are busy elsewhere.
#include <doctest/doctest.h>

#include <atomic>
#include <future>
#include <stdexcept>
#include <thread>
#include <vector>

#include <omp.h>

#include "lapis/core/parallel_for.h"

using namespace lapis;

namespace {

// Sets OpenMP's thread count for the scope (parallel_threads() follows it).
struct Threads {
  int before = omp_get_max_threads();
  explicit Threads(int n) { omp_set_num_threads(n); }
  ~Threads() { omp_set_num_threads(before); }
};

}  // namespace

TEST_CASE("core: parallel_for visits every index exactly once, in chunks of at most the grain") {
  const Threads four(4);
  for (const std::ptrdiff_t n : {0, 1, 7, 1000, 100003})
    for (const std::ptrdiff_t grain : {1, 3, 256, 200000}) {
      std::vector<std::atomic<int>> seen(static_cast<size_t>(n) + 10);
      std::atomic<bool> too_long{false};
      core::parallel_for(10, 10 + n, grain, [&](std::ptrdiff_t lo, std::ptrdiff_t hi) {
        if (hi - lo > grain || lo >= hi) too_long = true;
        for (std::ptrdiff_t i = lo; i < hi; ++i) seen[static_cast<size_t>(i)]++;
      });
      CHECK_FALSE(too_long);
      int wrong = 0;
      for (std::ptrdiff_t i = 0; i < n + 10; ++i) wrong += seen[static_cast<size_t>(i)] != (i >= 10 ? 1 : 0);
      CHECK_MESSAGE(wrong == 0, "n ", n, " grain ", grain);
    }
}

TEST_CASE("core: parallel_sum is the same on one thread and on several") {
  auto sum = [] {
    return core::parallel_sum<double>(0, 1000000, 997, [](std::ptrdiff_t lo, std::ptrdiff_t hi) {
      double s = 0;
      for (std::ptrdiff_t i = lo; i < hi; ++i) s += 1.0 / (1.0 + static_cast<double>(i) * 0.37);
      return s;
    });
  };
  double one, four;
  {
    const Threads t(1);
    one = sum();
  }
  {
    const Threads t(4);
    four = sum();
    for (int repeat = 0; repeat < 20; ++repeat) CHECK(sum() == four);  // bitwise, not within a tolerance
  }
  CHECK(one == four);
}

TEST_CASE("core: an exception in a chunk reaches the caller, and the next loop runs normally") {
  const Threads four(4);
  CHECK_THROWS_WITH_AS(core::parallel_for(0, 10000, 10,
                                          [](std::ptrdiff_t lo, std::ptrdiff_t) {
                                            if (lo == 5000) throw std::runtime_error("chunk 500 failed");
                                          }),
                       "chunk 500 failed", std::runtime_error);
  std::atomic<long> total{0};
  core::parallel_for(0, 10000, 10, [&](std::ptrdiff_t lo, std::ptrdiff_t hi) { total += hi - lo; });
  CHECK(total == 10000);
}

TEST_CASE("core: a nested loop and a loop beside a busy one run serially instead of waiting") {
  const Threads four(4);
  std::atomic<long> inner{0};
  core::parallel_for(0, 64, 1, [&](std::ptrdiff_t, std::ptrdiff_t) {
    core::parallel_for(0, 100, 7, [&](std::ptrdiff_t lo, std::ptrdiff_t hi) { inner += hi - lo; });
  });
  CHECK(inner == 6400);

  // A loop on another thread holds the workers until this thread's loop has finished: if this
  // loop waited for them, it would never finish.
  std::promise<void> started, finished;
  std::shared_future<void> done = finished.get_future().share();
  std::thread other([&] {
    std::atomic<bool> told{false};
    core::parallel_for(0, 8, 1, [&](std::ptrdiff_t, std::ptrdiff_t) {
      if (!told.exchange(true)) started.set_value();
      done.wait();
    });
  });
  started.get_future().wait();
  long mine = 0;
  core::parallel_for(0, 1000, 10, [&](std::ptrdiff_t lo, std::ptrdiff_t hi) { mine += hi - lo; });
  CHECK(mine == 1000);
  finished.set_value();
  other.join();
}
