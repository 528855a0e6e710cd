#include "lapis/solver/blas_threads.h"

#include <dlfcn.h>

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

ScopedBlasThreads::ScopedBlasThreads(int threads) {
  const OpenBlas& b = openblas();
  if (!b.set || threads < 1) return;
  previous_ = b.get();
  b.set(threads);
}

ScopedBlasThreads::~ScopedBlasThreads() {
  if (previous_ > 0) openblas().set(previous_);
}

bool ScopedBlasThreads::available() { return openblas().set != nullptr; }

int ScopedBlasThreads::current() { return available() ? openblas().get() : 0; }

}  // namespace lapis::solver
