#include "tree_split.h"

#include <algorithm>
#include <numeric>

namespace lapis::solver::detail {
namespace {

// Longest-processing-time assignment of subtrees (by weight) to `bins`; returns the heaviest
// bin's load and, in `bin_of`, each subtree's bin.
double assign_bins(const std::vector<int>& roots, const std::vector<double>& weight, int bins,
                   std::vector<int>& bin_of) {
  std::vector<int> order(roots.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return weight[static_cast<size_t>(roots[static_cast<size_t>(a)])] >
           weight[static_cast<size_t>(roots[static_cast<size_t>(b)])];
  });
  std::vector<double> load(static_cast<size_t>(bins), 0.0);
  bin_of.assign(roots.size(), 0);
  for (int k : order) {
    const auto lightest = std::min_element(load.begin(), load.end()) - load.begin();
    bin_of[static_cast<size_t>(k)] = static_cast<int>(lightest);
    load[static_cast<size_t>(lightest)] += weight[static_cast<size_t>(roots[static_cast<size_t>(k)])];
  }
  return *std::max_element(load.begin(), load.end());
}

TreeSplit whole_tree(int n) {
  TreeSplit s;
  s.subtrees.assign(1, {});
  if (n > 0) s.subtrees[0].emplace_back(0, n - 1);
  s.in_subtree.assign(static_cast<size_t>(n), 1);
  return s;
}

}  // namespace

TreeSplit split_tree(const std::vector<int>& parent, const std::vector<double>& work, int threads) {
  const int n = static_cast<int>(parent.size());
  threads = std::max(1, threads);
  if (threads == 1 || n == 0) return whole_tree(n);

  // Subtree weights and children lists; children have smaller indices than their parent, so
  // one ascending sweep accumulates the weights.
  std::vector<double> weight(work);
  std::vector<int> child_start(static_cast<size_t>(n) + 1, 0), children(static_cast<size_t>(n));
  std::vector<int> roots;
  std::vector<int> subtree_size(static_cast<size_t>(n), 1), first_descendant(static_cast<size_t>(n));
  std::iota(first_descendant.begin(), first_descendant.end(), 0);
  for (int j = 0; j < n; ++j) {
    const int p = parent[static_cast<size_t>(j)];
    if (p < 0) {
      roots.push_back(j);
      continue;
    }
    weight[static_cast<size_t>(p)] += weight[static_cast<size_t>(j)];
    subtree_size[static_cast<size_t>(p)] += subtree_size[static_cast<size_t>(j)];
    first_descendant[static_cast<size_t>(p)] =
        std::min(first_descendant[static_cast<size_t>(p)], first_descendant[static_cast<size_t>(j)]);
    ++child_start[static_cast<size_t>(p) + 1];
  }
  std::partial_sum(child_start.begin(), child_start.end(), child_start.begin());
  {
    std::vector<int> fill(child_start.begin(), child_start.end() - 1);
    for (int j = 0; j < n; ++j)
      if (const int p = parent[static_cast<size_t>(j)]; p >= 0)
        children[static_cast<size_t>(fill[static_cast<size_t>(p)]++)] = j;
  }
  const double total = std::accumulate(roots.begin(), roots.end(), 0.0,
                                       [&](double a, int r) { return a + weight[static_cast<size_t>(r)]; });

  // The nodes split off (the separators' chains) are solved serially: stop when they hold a
  // third of the work, more splitting would only move work there.
  std::vector<int> frontier = roots, bin_of;
  double top_weight = 0;
  for (int splits = 0; splits < 256; ++splits) {
    const double max_load = assign_bins(frontier, weight, threads, bin_of);
    const double ideal = (total - top_weight) / threads;
    if (max_load <= 1.05 * ideal || top_weight > total / 3) break;
    const auto heaviest = std::max_element(frontier.begin(), frontier.end(), [&](int a, int b) {
      return weight[static_cast<size_t>(a)] < weight[static_cast<size_t>(b)];
    });
    int node = *heaviest;
    frontier.erase(heaviest);
    for (;;) {
      top_weight += work[static_cast<size_t>(node)];
      const int c0 = child_start[static_cast<size_t>(node)], c1 = child_start[static_cast<size_t>(node) + 1];
      if (c1 - c0 != 1) {
        frontier.insert(frontier.end(), children.begin() + c0, children.begin() + c1);
        break;
      }
      node = children[static_cast<size_t>(c0)];
    }
  }
  assign_bins(frontier, weight, threads, bin_of);

  // A subtree that is not the contiguous range [first_descendant, root] (not postordered)
  // would break the kernels' "row <= root: this thread's" test: one thread then.
  TreeSplit s;
  s.subtrees.assign(static_cast<size_t>(threads), {});
  s.in_subtree.assign(static_cast<size_t>(n), 0);
  for (size_t k = 0; k < frontier.size(); ++k) {
    const int root = frontier[k];
    const int first = root - subtree_size[static_cast<size_t>(root)] + 1;
    if (first < 0 || first_descendant[static_cast<size_t>(root)] != first) return whole_tree(n);
    s.subtrees[static_cast<size_t>(bin_of[k])].emplace_back(first, root);
    std::fill(s.in_subtree.begin() + first, s.in_subtree.begin() + root + 1, 1);
  }
  for (auto& mine : s.subtrees) std::sort(mine.begin(), mine.end());
  return s;
}

}  // namespace lapis::solver::detail
