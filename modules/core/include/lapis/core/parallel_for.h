// Parallel loops for the per-frame paths (ARAP iterations, implicit editing's polar step, the
// solver's triangular solves), where a frame must not wait on a thread that is not running.
//
// An OpenMP team ends every loop at a barrier that waits for each member, and libgomp's members
// spin while they wait. With other work on the cores (a renderer, a compiler, the user's
// browser) one member is often descheduled, and the whole frame waits for it: on a 2-core
// machine with one busy core, ARAP on a 2.8K-vertex mesh took up to 164 ms a frame on two
// threads against 3.5 ms on one (bench_frame_jitter). Here the calling thread takes chunks of
// the range itself, workers join as they wake, and the call returns when every chunk is done
// and no worker is still inside one: a worker that never woke up holds nothing.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

namespace lapis::core {

// Threads a parallel loop may use now: OpenMP's max-threads setting of the calling thread
// (OMP_NUM_THREADS, omp_set_num_threads), so one knob sets every parallel part.
int parallel_threads();

// Runs body(lo, hi) on consecutive chunks [lo, hi) of [begin, end) of at most `grain`
// indices each, on the calling thread and the shared workers (parallel_threads() in all, at
// most one per core). Chunks run in no particular
// order and concurrently, so body must only write data of its own indices. Runs serially
// when one thread is allowed, the range is a single chunk, or the workers are busy with
// another loop (a nested or concurrent call). An exception thrown by body stops the loop and
// is rethrown here after every running chunk has ended.
void parallel_for(std::ptrdiff_t begin, std::ptrdiff_t end, std::ptrdiff_t grain,
                  const std::function<void(std::ptrdiff_t, std::ptrdiff_t)>& body);

// Σ over chunks of body(lo, hi), the chunk sums added in chunk order: the result is the same
// whichever thread ran which chunk, unlike an OpenMP reduction.
template <class T, class Body>
T parallel_sum(std::ptrdiff_t begin, std::ptrdiff_t end, std::ptrdiff_t grain, Body body) {
  if (end <= begin) return T{};
  const std::ptrdiff_t chunks = (end - begin + grain - 1) / grain;
  std::vector<T> partial(static_cast<std::size_t>(chunks), T{});
  parallel_for(begin, end, grain, [&](std::ptrdiff_t lo, std::ptrdiff_t hi) {
    partial[static_cast<std::size_t>((lo - begin) / grain)] = body(lo, hi);
  });
  T total{};
  for (const T& p : partial) total += p;
  return total;
}

}  // namespace lapis::core
