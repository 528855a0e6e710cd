#include "page_populate.h"

#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <system_error>

#ifndef MADV_POPULATE_WRITE
#define MADV_POPULATE_WRITE 23  // Linux 5.14; older headers lack the name
#endif

namespace lapis::solver::detail {
namespace {

// One transparent huge page: the helper checks for the stop flag between chunks.
constexpr std::uintptr_t kChunk = std::uintptr_t{2} << 20;

}  // namespace

PagePopulator::PagePopulator(void* data, std::size_t bytes, std::size_t min_bytes) {
  if (!data || bytes < min_bytes) return;
  const auto page = static_cast<std::uintptr_t>(::sysconf(_SC_PAGESIZE));
  // Whole pages inside the range: madvise wants a page-aligned start, and a partial page at
  // either end is left to the owner (it may share the page with other live data).
  const std::uintptr_t first = (reinterpret_cast<std::uintptr_t>(data) + page - 1) / page * page;
  const std::uintptr_t last = (reinterpret_cast<std::uintptr_t>(data) + bytes) / page * page;
  if (last <= first) return;
  try {
    helper_ = std::thread([this, first, last] { populate(first, last); });
  } catch (const std::system_error&) {
    // No thread to be had (the process is at its limit): the owner faults its pages itself.
  }
}

void PagePopulator::populate(std::uintptr_t first, std::uintptr_t last) {
  std::uintptr_t end = last;
  while (end > first && !stop_.load(std::memory_order_relaxed)) {
    // Chunks aligned to kChunk (the first one from `last` may be shorter), never below first.
    const std::uintptr_t from = end - first > kChunk ? std::max((end - kChunk) / kChunk * kChunk, first) : first;
    if (::madvise(reinterpret_cast<void*>(from), end - from, MADV_POPULATE_WRITE) != 0) return;
    populated_.fetch_add(end - from, std::memory_order_relaxed);
    end = from;
  }
}

void PagePopulator::wait() {
  if (helper_.joinable()) helper_.join();
}

PagePopulator::~PagePopulator() {
  stop_.store(true, std::memory_order_relaxed);
  wait();
}

}  // namespace lapis::solver::detail
