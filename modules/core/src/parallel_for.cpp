#include "lapis/core/parallel_for.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>

#include <omp.h>

namespace lapis::core {
namespace {

// One loop: lives on the calling thread's stack for the duration of parallel_for.
struct Job {
  const std::function<void(std::ptrdiff_t, std::ptrdiff_t)>* body;
  std::ptrdiff_t begin, end, grain, chunks;
  std::atomic<std::ptrdiff_t> next{0};  // next chunk to claim
  std::atomic<int> seats{0};            // workers that may still join
  std::mutex error_mutex;
  std::exception_ptr error;

  // Inside a chunk run on the workers, OpenMP regions (Eigen's products among them) and nested
  // loops run on one thread: a chunk already has its core, and a team opened from it would
  // wait on cores that the loop's other chunks hold.
  void run_chunks(bool on_workers) {
    const int threads_before = omp_get_max_threads();
    if (on_workers) omp_set_num_threads(1);
    for (std::ptrdiff_t c; (c = next.fetch_add(1)) < chunks;) {
      const std::ptrdiff_t lo = begin + c * grain;
      try {
        (*body)(lo, std::min(end, lo + grain));
      } catch (...) {
        std::lock_guard lock(error_mutex);
        if (!error) error = std::current_exception();
        next.store(chunks);  // no further chunks start
      }
    }
    if (on_workers) omp_set_num_threads(threads_before);
  }
};

// Workers sleep on `wake` between loops. A worker joins the published job by counting itself
// in `inside` before it reads `job`; the caller unpublishes the job before it waits for
// `inside` to drop to zero. Both sides use sequentially consistent operations, so either the
// caller sees the worker inside (and waits for it) or the worker sees no job (and leaves).
class Pool {
 public:
  static Pool& instance() {
    static Pool* pool = new Pool;  // never destroyed: workers may still sleep at exit
    return *pool;
  }

  bool try_acquire() {
    bool expected = false;
    return busy_.compare_exchange_strong(expected, true);
  }
  void release() { busy_.store(false); }

  void run(Job& job, int threads) {
    job.seats.store(threads - 1);
    job_.store(&job);
    wake_.fetch_add(1);
    for (int i = 1; i < threads; ++i) wake_.notify_one();  // the sleepers beyond the seats stay asleep
    job.run_chunks(true);
    job_.store(nullptr);
    for (int in; (in = inside_.load()) != 0;) inside_.wait(in);
  }

  // Starts workers up to `workers`; false when the system refuses a thread.
  bool grow(int workers) {
    try {
      while (static_cast<int>(workers_.size()) < workers) workers_.emplace_back([this] { work(); });
    } catch (const std::system_error&) {
      return false;
    }
    return true;
  }

 private:
  void work() {
    std::uint32_t seen = wake_.load();
    for (;;) {
      spin_while_unchanged(seen);
      wake_.wait(seen);
      seen = wake_.load();
      inside_.fetch_add(1);
      Job* job = job_.load();
      if (job && job->seats.fetch_sub(1) > 0) job->run_chunks(true);
      if (inside_.fetch_sub(1) == 1) inside_.notify_all();
    }
  }

  // A frame's loops come back to back (ARAP: right-hand side, solve, rotation fits), and a
  // worker asleep in the kernel wakes too late to help with a loop of a few hundred
  // microseconds. So a worker first watches for the next loop for a short while, yielding
  // its core to anything else that is runnable, and only then sleeps.
  void spin_while_unchanged(std::uint32_t seen) const {
    using clock = std::chrono::steady_clock;
    const auto until = clock::now() + std::chrono::microseconds(200);
    while (wake_.load(std::memory_order_relaxed) == seen && clock::now() < until)
      for (int i = 0; i < 64 && wake_.load(std::memory_order_relaxed) == seen; ++i) std::this_thread::yield();
  }

  std::atomic<bool> busy_{false};
  std::atomic<Job*> job_{nullptr};
  std::atomic<std::uint32_t> wake_{0};
  std::atomic<int> inside_{0};
  std::vector<std::thread> workers_;  // grown only by the thread that holds busy_
};

}  // namespace

int parallel_threads() { return std::max(1, omp_get_max_threads()); }

namespace {

// More threads than cores only adds preemption, which is what the pool is there to avoid.
int cores() {
  static const int n = std::max(1u, std::thread::hardware_concurrency());
  return n;
}

}  // namespace

void parallel_for(std::ptrdiff_t begin, std::ptrdiff_t end, std::ptrdiff_t grain,
                  const std::function<void(std::ptrdiff_t, std::ptrdiff_t)>& body) {
  if (end <= begin) return;
  grain = std::max<std::ptrdiff_t>(grain, 1);
  const std::ptrdiff_t chunks = (end - begin + grain - 1) / grain;
  const int threads = static_cast<int>(std::min<std::ptrdiff_t>(std::min(parallel_threads(), cores()), chunks));
  Pool& pool = Pool::instance();
  Job job;
  job.body = &body;
  job.begin = begin;
  job.end = end;
  job.grain = grain;
  job.chunks = chunks;
  if (threads > 1 && pool.try_acquire()) {
    if (pool.grow(threads - 1)) pool.run(job, threads);
    pool.release();
  }
  job.run_chunks(false);  // serially, when the loop did not go to the workers (or is done already)
  if (job.error) std::rethrow_exception(job.error);
}

}  // namespace lapis::core
