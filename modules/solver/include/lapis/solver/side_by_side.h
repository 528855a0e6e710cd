// Two set-ups at once (assembly, ordering, factorization), for a user with two independent
// systems, such as implicit Laplacian editing's Eq. 2.8 and Eq. 2.10. The solver layer, which
// owns every factorization, decides how they share the machine: one BLAS thread each, since
// OpenBLAS' idle threads busy-wait on the cores the other factorization needs (a 16K-vertex
// merge's two factorizations: 1.2 s with OpenBLAS' default threads, 0.85 s with one each).
#pragma once

#include <functional>

namespace lapis::solver {

// Runs `side` on a second thread while `main` runs on this one, and returns when both are
// done. Throws main's exception if it threw (after side has finished), else side's. Both may
// use the solver (each on its own objects).
void side_by_side(const std::function<void()>& main, const std::function<void()>& side);

}  // namespace lapis::solver
