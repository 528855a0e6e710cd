#include "lapis/solver/ordering.h"

#include <algorithm>
#include <string>

#include "checks.h"
#include "cholmod_context.h"

namespace lapis::solver {
namespace {

// The skeleton's pattern as symmetric adjacency lists without the diagonal.
struct Adjacency {
  std::vector<int> start, neighbours;
};

Adjacency symmetric_adjacency(const SparseMatrix& S) {
  const int n = static_cast<int>(S.cols());
  Adjacency g;
  g.start.assign(static_cast<size_t>(n) + 1, 0);
  for (int j = 0; j < n; ++j)
    for (SparseMatrix::InnerIterator e(S, j); e; ++e)
      if (e.row() != j) ++g.start[static_cast<size_t>(j) + 1], ++g.start[static_cast<size_t>(e.row()) + 1];
  for (int v = 0; v < n; ++v) g.start[static_cast<size_t>(v) + 1] += g.start[static_cast<size_t>(v)];
  g.neighbours.resize(static_cast<size_t>(g.start.back()));
  std::vector<int> fill(g.start.begin(), g.start.end() - 1);
  for (int j = 0; j < n; ++j)
    for (SparseMatrix::InnerIterator e(S, j); e; ++e)
      if (const int i = static_cast<int>(e.row()); i != j)
        g.neighbours[static_cast<size_t>(fill[static_cast<size_t>(j)]++)] = i,
        g.neighbours[static_cast<size_t>(fill[static_cast<size_t>(i)]++)] = j;
  for (int v = 0; v < n; ++v) {
    auto first = g.neighbours.begin() + g.start[static_cast<size_t>(v)];
    auto last = g.neighbours.begin() + g.start[static_cast<size_t>(v) + 1];
    std::sort(first, last);
    // Entries (i, j) and (j, i) both stored give each edge twice.
    const auto end = std::unique(first, last);
    std::fill(end, last, -1);
  }
  return g;
}

// A part of the unknowns to dissect, or a separator to number after its two sides.
struct Task {
  std::vector<int> unknowns;
  bool separator = false;
};

}  // namespace

std::vector<int> skeleton_nested_dissection(const SparseMatrix& A_in, const SparseMatrix& skeleton_in,
                                            SkeletonDissectionOptions options) {
  constexpr const char* fn = "solver::skeleton_nested_dissection()";
  detail::require_square(A_in, fn);
  detail::require_square(skeleton_in, fn);
  if (skeleton_in.rows() != A_in.rows())
    throw InvalidArgument(std::string(fn) + ": skeleton is " + std::to_string(skeleton_in.rows()) + " by " +
                          std::to_string(skeleton_in.cols()) + ", the matrix " + std::to_string(A_in.rows()) + " by " +
                          std::to_string(A_in.cols()));
  const SparseMatrix A = A_in.isCompressed() ? SparseMatrix() : SparseMatrix(A_in);
  const SparseMatrix& a = A_in.isCompressed() ? A_in : A;
  const int n = static_cast<int>(a.rows());
  if (n == 0) return {};
  const Adjacency g = symmetric_adjacency(skeleton_in);
  const int leaf = std::max(options.leaf_size, 2);

  detail::CholmodContext context;
  cholmod_common* c = context.get();
  std::vector<int> component(static_cast<size_t>(n), -1);  // CAMD's constraint set of each unknown
  int components = 0;
  std::vector<int> local(static_cast<size_t>(n), -1), side(static_cast<size_t>(n), -1);
  std::vector<char> crosses(static_cast<size_t>(n), 0);  // already in crossing[its side]
  std::vector<int> column_start, rows, partition;
  std::vector<double> ones;
  // Depth first, the separator task below its two sides: every part is numbered before the
  // separators above it, the order CAMD's constraint sets must have.
  std::vector<Task> stack;
  stack.push_back({std::vector<int>(static_cast<size_t>(n)), false});
  for (int v = 0; v < n; ++v) stack.back().unknowns[static_cast<size_t>(v)] = v;
  while (!stack.empty()) {
    Task task = std::move(stack.back());
    stack.pop_back();
    std::vector<int>& part = task.unknowns;
    const int m = static_cast<int>(part.size());
    auto number_as_one = [&] {
      if (part.empty()) return;
      for (int v : part) component[static_cast<size_t>(v)] = components;
      ++components;
    };
    if (task.separator || m <= leaf) {
      number_as_one();
      continue;
    }
    // The skeleton restricted to the part, lower triangle (CHOLMOD's stype = -1).
    for (int k = 0; k < m; ++k) local[static_cast<size_t>(part[static_cast<size_t>(k)])] = k;
    column_start.assign(static_cast<size_t>(m) + 1, 0);
    rows.clear();
    for (int k = 0; k < m; ++k) {
      const int v = part[static_cast<size_t>(k)];
      const size_t first = rows.size();
      for (int e = g.start[static_cast<size_t>(v)]; e < g.start[static_cast<size_t>(v) + 1]; ++e) {
        const int u = g.neighbours[static_cast<size_t>(e)];
        if (u >= 0 && local[static_cast<size_t>(u)] > k) rows.push_back(local[static_cast<size_t>(u)]);
      }
      std::sort(rows.begin() + static_cast<std::ptrdiff_t>(first), rows.end());
      column_start[static_cast<size_t>(k) + 1] = static_cast<int>(rows.size());
    }
    ones.assign(std::max<size_t>(rows.size(), 1), 1.0);
    cholmod_sparse S{};
    S.nrow = S.ncol = static_cast<size_t>(m);
    S.nzmax = std::max<size_t>(rows.size(), 1);
    S.p = column_start.data();
    S.i = rows.empty() ? column_start.data() : rows.data();
    S.x = ones.data();
    S.stype = -1;
    S.itype = CHOLMOD_INT;
    S.xtype = CHOLMOD_REAL;
    S.dtype = CHOLMOD_DOUBLE;
    S.sorted = 1;
    S.packed = 1;
    partition.assign(static_cast<size_t>(m), 0);
    {
      const std::lock_guard metis(detail::metis_mutex());  // see cholmod_context.h
      cholmod_bisect(&S, nullptr, 0, /*compress=*/0, partition.data(), c);
    }
    context.check(fn, "cholmod_bisect");
    for (int k = 0; k < m; ++k)
      side[static_cast<size_t>(part[static_cast<size_t>(k)])] = partition[static_cast<size_t>(k)];
    // Widen: unknowns of side s coupled in A to side 1 − s join the separator, for the side
    // that gives the smaller separator. The skeleton's separator is only as wide as its own
    // edges; A's couplings reach further.
    // Each coupling is read once, from its lower-triangle entry (u > v), and marks both ends.
    std::vector<int> crossing[2];
    for (int v : part) {
      const int s = side[static_cast<size_t>(v)];
      if (s == 2) continue;
      for (SparseMatrix::InnerIterator e(a, v); e; ++e) {
        const int u = static_cast<int>(e.row());
        if (u <= v || local[static_cast<size_t>(u)] < 0 || side[static_cast<size_t>(u)] != 1 - s) continue;
        for (const int end : {v, u})
          if (!crosses[static_cast<size_t>(end)]) {
            crosses[static_cast<size_t>(end)] = 1;
            crossing[side[static_cast<size_t>(end)]].push_back(end);
          }
      }
    }
    for (const auto& list : crossing)
      for (int v : list) crosses[static_cast<size_t>(v)] = 0;
    for (int v : crossing[crossing[0].size() <= crossing[1].size() ? 0 : 1]) side[static_cast<size_t>(v)] = 2;
    Task left, right, separator{{}, true};
    for (int v : part) {
      const int s = side[static_cast<size_t>(v)];
      (s == 0 ? left : s == 1 ? right : separator).unknowns.push_back(v);
      local[static_cast<size_t>(v)] = side[static_cast<size_t>(v)] = -1;
    }
    if (left.unknowns.empty() || right.unknowns.empty()) {
      number_as_one();  // nothing to separate (a clique, or a failed bisection)
      continue;
    }
    stack.push_back(std::move(separator));
    stack.push_back(std::move(right));
    stack.push_back(std::move(left));
  }

  std::vector<int> perm(static_cast<size_t>(n));
  cholmod_sparse view = detail::sparse_view(a, -1);
  cholmod_camd(&view, nullptr, 0, component.data(), perm.data(), c);
  context.check(fn, "cholmod_camd");
  return perm;
}

}  // namespace lapis::solver
