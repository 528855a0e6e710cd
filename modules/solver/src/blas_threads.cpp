#include "lapis/solver/blas_threads.h"

#include <dlfcn.h>

#include <mutex>

namespace lapis::solver {
namespace {

using SetThreads = void (*)(int);
using GetThreads = int (*)();

// Looked up once in the libraries already loaded (CHOLMOD's BLAS).
struct OpenBlas {
  SetThreads set = nullptr;
  GetThreads get = nullptr;
  OpenBlas() {
    set = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
    get = reinterpret_cast<GetThreads>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
    if (!set || !get) set = nullptr, get = nullptr;
  }
};

const OpenBlas& openblas() {
  static const OpenBlas library;
  return library;
}

}  // namespace

// Guards may overlap (two deformers set up on two threads): the first saves the count, the
// last restores it, so overlapping guards cannot leave the process at one thread.
std::mutex guard_mutex;
int open_guards = 0;
int saved_threads = 0;

ScopedBlasThreads::ScopedBlasThreads(int threads) {
  const OpenBlas& b = openblas();
  if (!b.set || threads < 1) return;
  const std::lock_guard lock(guard_mutex);
  if (open_guards++ == 0) saved_threads = b.get();
  b.set(threads);
  active_ = true;
}

ScopedBlasThreads::~ScopedBlasThreads() {
  if (!active_) return;
  const std::lock_guard lock(guard_mutex);
  if (--open_guards == 0) openblas().set(saved_threads);
}

bool ScopedBlasThreads::available() { return openblas().set != nullptr; }

int ScopedBlasThreads::current() { return available() ? openblas().get() : 0; }

}  // namespace lapis::solver
