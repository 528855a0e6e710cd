// Solving with a CHOLMOD simplicial LDLᵀ factor (the form cholmod_updown keeps), in parallel
// over independent subtrees of the elimination tree.
//
// Why not cholmod_solve: after an update/downdate the factor is simplicial, and CHOLMOD's
// simplicial solve is serial and keeps the right-hand sides column by column, so each row of
// L touches one cache line per right-hand side. At the hair-sketching size (N = 37, 38M
// entries in L) a solve streams all of L twice (forward, backward) and that is its whole
// cost. Here the right-hand sides of a row are stored together, supernode runs share their
// row indices, and the subtrees under the top separators of the nested-dissection ordering
// run on separate threads: they touch disjoint columns of L. Not for concurrent use of one
// factor (the schedule is cached), like cholmod_solve with its workspace.
#pragma once

#include <cholmod.h>

#include <vector>

#include "lapis/solver/types.h"

namespace lapis::solver::detail {

// A run of consecutive columns j, j+1, ... of L in which each column's pattern is the next
// column's plus its own diagonal (a supernode of the simplicial factor): solved together, so
// the shared row indices and right-hand-side rows are read once for the whole run.
struct ColumnRun {
  int first = 0;
  int count = 1;
  int limit = 0;  // rows <= limit belong to the same thread; above: the shared ancestors
};

// Which thread solves which columns. Built once per factor pattern (an update/downdate that
// adds fill changes the elimination tree: rebuild then).
struct SubtreeSchedule {
  int n = 0;
  std::vector<std::vector<ColumnRun>> runs;  // per thread, ascending: whole subtrees
  std::vector<ColumnRun> top;                // ascending: the ancestors of those subtrees
  std::vector<int> top_slot;                 // per column among the ancestors: its index
  int top_columns = 0;
  long long pattern_entries = 0;  // Σ nnz of L's columns when built (a pattern check)
};

// Splits the elimination tree of the simplicial factor L into `threads` balanced sets of
// whole subtrees (balanced by entries of L) plus the ancestors they share. Each subtree must
// be a contiguous range of columns (CHOLMOD postorders its elimination tree); if one is not,
// the schedule falls back to a single thread.
SubtreeSchedule schedule_subtrees(const cholmod_factor& L, int threads);

// True when `schedule` was built for L's current pattern.
bool schedule_matches(const SubtreeSchedule& schedule, const cholmod_factor& L);

// X with A X = B, where L D Lᵀ = P A Pᵀ is the simplicial LDLᵀ factor L (L->Perm = P).
DenseMatrix solve_simplicial_ldlt(const cholmod_factor& L, const SubtreeSchedule& schedule, const DenseMatrix& B);

}  // namespace lapis::solver::detail
