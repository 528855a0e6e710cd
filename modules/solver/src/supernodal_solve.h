// Solving with a CHOLMOD supernodal LLᵀ factor, in parallel over independent subtrees of the
// supernodal elimination tree, all right-hand sides of a row stored together.
//
// Why not cholmod_solve: it is serial, keeps the right-hand sides column by column and calls
// BLAS (dtrsm, dgemm) once per supernode, which on a mesh factor — tens of thousands of small
// supernodes, 3 right-hand sides — costs more than streaming L itself. A solve reads all of L
// twice (forward, backward) and that should be its whole cost: here each supernode's dense
// block is read once per pass, four columns at a time against a contiguous buffer of its rows,
// the subtrees under the top separators run on separate threads, and the big top supernodes
// are split over the threads row- (forward) or column-wise (backward).
#pragma once

#include <cholmod.h>

#include <vector>

#include "lapis/solver/types.h"

namespace lapis::solver::detail {

// Which thread solves which supernodes; depends only on the factor's symbolic structure.
struct SupernodalSchedule {
  struct Range {
    int first = 0, last = 0;  // supernodes first..last (a whole subtree, or several)
    int limit = 0;            // last column of the subtree: rows above it are shared ancestors
  };
  std::vector<std::vector<Range>> subtrees;  // per thread, ascending
  std::vector<int> top;                      // ascending: the supernodes the subtrees share
  std::vector<int> top_slot;                 // per column of a top supernode: its buffer row
  int top_columns = 0;
  int max_rows = 0;  // the tallest supernode's row count
  int threads = 1;
};

// `threads` = 0: OpenMP's default.
SupernodalSchedule schedule_supernodes(const cholmod_factor& L, int threads);

// X with A X = B, where L Lᵀ = P A Pᵀ is the supernodal factor L (L->Perm = P).
DenseMatrix solve_supernodal_llt(const cholmod_factor& L, const SupernodalSchedule& schedule, const DenseMatrix& B);

}  // namespace lapis::solver::detail
