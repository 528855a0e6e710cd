// Which allocator this benchmark runs on: the tables and JSON results name it, because their
// figures depend on it (see cmake/LapisAllocator.cmake).
#pragma once

#include <dlfcn.h>

#include <cstddef>
#include <string>

namespace lapis::bench {

// "jemalloc, thp:always, dirty_decay_ms:-1" when the process allocates through jemalloc (named
// with the two options that change Lapis' timings), "system malloc" otherwise.
inline std::string allocator_name() {
  using Mallctl = int (*)(const char*, void*, std::size_t*, void*, std::size_t);
  const auto mallctl = reinterpret_cast<Mallctl>(dlsym(RTLD_DEFAULT, "mallctl"));
  if (!mallctl) return "system malloc";
  std::string name = "jemalloc";
  const char* thp = nullptr;
  std::size_t size = sizeof(thp);
  if (mallctl("opt.thp", static_cast<void*>(&thp), &size, nullptr, 0) == 0 && thp) name += std::string(", thp:") + thp;
  long decay = 0;  // ssize_t in jemalloc
  size = sizeof(decay);
  if (mallctl("opt.dirty_decay_ms", static_cast<void*>(&decay), &size, nullptr, 0) == 0)
    name += ", dirty_decay_ms:" + std::to_string(decay);
  return name;
}

}  // namespace lapis::bench
