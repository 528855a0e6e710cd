// The machine's memory read bandwidth, on one thread and on all. Sparse triangular solves
// and update/downdates stream their factor from memory, so their times scale with it: the
// benchmarks print it beside their figures, which makes figures from different machines
// comparable.
#pragma once

#include <omp.h>

#include <algorithm>
#include <cstddef>
#include <vector>

#include <nlohmann/json.hpp>

#include "lapis_bench.h"

namespace lapis::bench {

struct MemoryBandwidth {
  double one_thread_gbs = 0;
  double all_threads_gbs = 0;
  int threads = 1;
  nlohmann::json to_json() const {
    return {{"read_gbs_one_thread", one_thread_gbs}, {"read_gbs_all_threads", all_threads_gbs}, {"threads", threads}};
  }
};

// Best of three sums over `bytes` of doubles (far beyond the last-level cache), per thread count.
inline MemoryBandwidth measure_memory_bandwidth(std::size_t bytes = std::size_t{256} << 20) {
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(bytes / sizeof(double));
  std::vector<double> a(static_cast<std::size_t>(n));
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t i = 0; i < n; ++i) a[static_cast<std::size_t>(i)] = 1.0;  // first touch, spread
  MemoryBandwidth out;
  out.threads = omp_get_max_threads();
  volatile double sink = 0;
  auto best_gbs = [&](int threads) {
    double best = 0;
    for (int rep = 0; rep < 3; ++rep) {
      double sum = 0;
      const double ms = time_ms([&] {
#pragma omp parallel for schedule(static) reduction(+ : sum) num_threads(threads)
        for (std::ptrdiff_t i = 0; i < n; ++i) sum += a[static_cast<std::size_t>(i)];
      });
      sink = sink + sum;
      best = std::max(best, static_cast<double>(bytes) / (ms * 1e6));
    }
    return best;
  };
  out.one_thread_gbs = best_gbs(1);
  out.all_threads_gbs = best_gbs(out.threads);
  return out;
}

}  // namespace lapis::bench
