// Gauss–Seidel on the field's normal equations (DᵀD + diag(w)) x = diag(w) c, restricted to
// the nodes near a constraint edit: the multigrid solver's warm start, relaxed where the
// edit put its error.
//
// Why: after an edit the previous field is wrong mostly next to the nodes whose constraints
// changed — a new constraint pins its node to a target, a removed one frees it — and that
// near field is sharp and local. The preconditioned CG spends its first iterations on it
// (its first step is almost all the new constraint rows: r·z drops 10⁶-fold). A few
// Gauss–Seidel sweeps over a small box around each changed node remove it for a fraction of
// one iteration's work and leave the smooth, global rest to the CG. Measured on the bundled
// head against a solve to 1e-12 (radius 3, 15 sweeps, see MultigridFieldOptions): the
// estimated error after 12 iterations of an edit at 250K drops from 7.9e-7 to 4.4e-7 (13
// iterations → 12), at 1M a stroke takes 13 iterations instead of 14 and an edit 14
// instead of 15, at 50K the edit's estimate after 12 falls from 4.9e-7 to 2.8e-7 (still 12
// iterations, so the solver's default budget leaves 50K out). Larger boxes did not help
// (radius 6: the same), fewer sweeps helped less (radius 3, 6 sweeps: 5.3e-7). A node
// update costs ~40 ns here: 4K nodes × 15 sweeps ≈ 2.5 ms, a tenth of an iteration at
// 250K.
#pragma once

#include <array>
#include <span>
#include <vector>

namespace lapis::hair_field::detail {

// The nodes within Chebyshev distance `radius` (in nodes) of any seed, ascending. `mark` is
// scratch of one entry per node, all zero on entry and on return.
std::vector<int> nodes_near(const std::array<int, 3>& dims, std::span<const int> seeds, int radius,
                            std::vector<char>& mark);

// `sweeps` Gauss–Seidel sweeps over `nodes` (ascending, distinct) of
// (DᵀD + diag(w)) x = diag(w) c, for the 3 columns of x and c (node-major, 3 per node);
// w per node. Each node update minimizes the energy ½xᵀAx − bᵀx over that node, so the
// energy never increases; nodes outside `nodes` are not written.
void gauss_seidel(const std::array<int, 3>& dims, const double* w, const double* c, std::span<const int> nodes,
                  int sweeps, double* x);

}  // namespace lapis::hair_field::detail
