// Which allocator this process runs on: for benchmark tables and reports, whose figures
// depend on it (see cmake/LapisAllocator.cmake).
#pragma once

#include <dlfcn.h>

#include <cstddef>
#include <string>

namespace lapis::core {

// "jemalloc, thp:always" when the process allocates through jemalloc (named with its
// transparent-huge-page option), "system malloc" otherwise.
inline std::string allocator_name() {
  using Mallctl = int (*)(const char*, void*, std::size_t*, void*, std::size_t);
  const auto mallctl = reinterpret_cast<Mallctl>(dlsym(RTLD_DEFAULT, "mallctl"));
  if (!mallctl) return "system malloc";
  const char* thp = nullptr;
  std::size_t size = sizeof(thp);
  if (mallctl("opt.thp", static_cast<void*>(&thp), &size, nullptr, 0) != 0 || !thp) return "jemalloc";
  return std::string("jemalloc, thp:") + thp;
}

}  // namespace lapis::core
