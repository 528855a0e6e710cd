// Splitting an elimination tree over threads for the triangular solves: whole subtrees go to
// threads, balanced by their work, and the ancestors they share (the top separators of a
// nested-dissection ordering) are left to be solved serially. Used by the simplicial kernel
// (tree of columns) and the supernodal one (tree of supernodes).
#pragma once

#include <utility>
#include <vector>

#include "lapis/core/parallel_for.h"

namespace lapis::solver::detail {

struct TreeSplit {
  // Per thread, ascending: the subtrees it owns as inclusive node ranges (first, root).
  std::vector<std::vector<std::pair<int, int>>> subtrees;
  // Per node: 1 when some thread's subtree contains it, 0 for the shared ancestors.
  std::vector<char> in_subtree;
};

// parent[j] > j (or -1 for a root) for every node, as in a postordered elimination tree;
// work[j] the node's own cost. Splits the heaviest subtree at its first branching node until
// the subtrees balance over the threads (within 5%) or the split-off ancestors hold a third of
// the work. With one thread, or when a subtree is not a contiguous range of nodes (the tree is
// not postordered), one thread gets the whole tree as the range (0, n − 1).
TreeSplit split_tree(const std::vector<int>& parent, const std::vector<double>& work, int threads);

// body(t) for every thread's share t in [0, shares) of a split, over core::parallel_for: the
// share of a thread that is not running is taken by one that is, so a solve never waits for
// a descheduled thread.
template <class F>
void for_each_piece(int shares, F body) {
  core::parallel_for(0, shares, 1, [&](std::ptrdiff_t lo, std::ptrdiff_t hi) {
    for (std::ptrdiff_t t = lo; t < hi; ++t) body(static_cast<int>(t));
  });
}

}  // namespace lapis::solver::detail
