#include "lapis/solver/types.h"
#include "lapis/solver/updatable_cholesky.h"

namespace lapis::solver {

const char* to_string(Backend b) { return b == Backend::Cholmod ? "cholmod" : "eigen"; }

const char* to_string(FactorKind k) { return k == FactorKind::Supernodal ? "supernodal" : "simplicial"; }

const char* to_string(ModifyMethod m) {
  switch (m) {
    case ModifyMethod::Auto:
      return "auto";
    case ModifyMethod::UpdateDowndate:
      return "update/downdate";
    case ModifyMethod::Refactorize:
      return "refactorize";
  }
  return "unknown";
}

}  // namespace lapis::solver
