// Splitting an elimination tree over threads for the triangular solves: whole subtrees go to
// threads, balanced by their work, and the ancestors they share (the top separators of a
// nested-dissection ordering) are left to be solved serially. Used by the simplicial kernel
// (tree of columns) and the supernodal one (tree of supernodes).
#pragma once

#include <utility>
#include <vector>

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

}  // namespace lapis::solver::detail
