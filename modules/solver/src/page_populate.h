// Private: fault in a freshly allocated array's pages on another thread while this one works
// through it from the front.
//
// On the virtual machines Lapis is measured on, the first write to a page of fresh memory
// costs ~2 ms per MB (the host backs the page, then the guest kernel zeroes it): a fresh
// process's 50K-vertex merge spent ~40% of its main thread's time in the kernel's page
// clearing, most of it inside CHOLMOD's numeric factorization, which zeroes each supernode
// of the factor right before computing it. PagePopulator takes that cost onto a helper thread
// (the second core is idle during the big factorization): it populates the range from its
// end backwards with madvise(MADV_POPULATE_WRITE), which maps writable zeroed pages without
// writing them, so it cannot race with the owner's writes. Pages already present (the part
// the owner has reached, memory the allocator reuses) cost it a page-table walk; it stops at
// the start of the range or when the owner is done. Where the call is not supported (Linux
// before 5.14) it stops at once and the owner faults its pages itself, as without it.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <thread>

namespace lapis::solver::detail {

class PagePopulator {
 public:
  // Starts populating [data, data + bytes) from the end when the range is at least
  // `min_bytes`; otherwise does nothing.
  PagePopulator(void* data, std::size_t bytes, std::size_t min_bytes = kMinBytes);
  // Stops the helper (it finishes the chunk in hand) and joins it.
  ~PagePopulator();
  PagePopulator(const PagePopulator&) = delete;
  PagePopulator& operator=(const PagePopulator&) = delete;

  // Bytes the helper populated so far (for tests).
  std::size_t populated_bytes() const { return populated_.load(std::memory_order_relaxed); }
  // Blocks until the helper has stopped by itself (range done or call unsupported).
  void wait();

  // Below this a thread costs more than the pages: 16 MB is ~30 ms of first touch here.
  static constexpr std::size_t kMinBytes = std::size_t{16} << 20;

 private:
  // The helper's loop over whole pages [first, last), from the end.
  void populate(std::uintptr_t first, std::uintptr_t last);

  std::atomic<bool> stop_{false};
  std::atomic<std::size_t> populated_{0};
  std::thread helper_;
};

}  // namespace lapis::solver::detail
