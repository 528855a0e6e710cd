#include "lapis/solver/ordering.h"

#include <algorithm>
#include <array>
#include <cmath>
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

// Work arrays of the dissection, sized once for all n unknowns. Between two parts, local and
// side are -1 and crosses is 0 everywhere.
struct Scratch {
  explicit Scratch(int n)
      : local(static_cast<size_t>(n), -1), side(static_cast<size_t>(n), -1), crosses(static_cast<size_t>(n), 0) {}
  std::vector<int> local;     // an unknown's index within the part being split
  std::vector<int> side;      // 0, 1, or 2 for the separator
  std::vector<char> crosses;  // already in crossing[its side] (widen_separator)
  std::vector<int> column_start, rows, partition;
  std::vector<double> ones;
};

// Bisects the skeleton restricted to the part with METIS (cholmod_bisect, on the lower
// triangle as CHOLMOD's stype = -1 wants) and writes each unknown's side.
void bisect_skeleton(const Adjacency& g, const std::vector<int>& part, Scratch& s, detail::CholmodContext& context,
                     const char* fn) {
  const int m = static_cast<int>(part.size());
  for (int k = 0; k < m; ++k) s.local[static_cast<size_t>(part[static_cast<size_t>(k)])] = k;
  s.column_start.assign(static_cast<size_t>(m) + 1, 0);
  s.rows.clear();
  for (int k = 0; k < m; ++k) {
    const int v = part[static_cast<size_t>(k)];
    const size_t first = s.rows.size();
    for (int e = g.start[static_cast<size_t>(v)]; e < g.start[static_cast<size_t>(v) + 1]; ++e) {
      const int u = g.neighbours[static_cast<size_t>(e)];
      if (u >= 0 && s.local[static_cast<size_t>(u)] > k) s.rows.push_back(s.local[static_cast<size_t>(u)]);
    }
    std::sort(s.rows.begin() + static_cast<std::ptrdiff_t>(first), s.rows.end());
    s.column_start[static_cast<size_t>(k) + 1] = static_cast<int>(s.rows.size());
  }
  s.ones.assign(std::max<size_t>(s.rows.size(), 1), 1.0);
  cholmod_sparse S{};
  S.nrow = S.ncol = static_cast<size_t>(m);
  S.nzmax = std::max<size_t>(s.rows.size(), 1);
  S.p = s.column_start.data();
  S.i = s.rows.empty() ? s.column_start.data() : s.rows.data();
  S.x = s.ones.data();
  S.stype = -1;
  S.itype = CHOLMOD_INT;
  S.xtype = CHOLMOD_REAL;
  S.dtype = CHOLMOD_DOUBLE;
  S.sorted = 1;
  S.packed = 1;
  s.partition.assign(static_cast<size_t>(m), 0);
  {
    const std::lock_guard metis(detail::metis_mutex());  // see cholmod_context.h
    cholmod_bisect(&S, nullptr, 0, /*compress=*/0, s.partition.data(), context.get());
  }
  context.check(fn, "cholmod_bisect");
  for (int k = 0; k < m; ++k)
    s.side[static_cast<size_t>(part[static_cast<size_t>(k)])] = s.partition[static_cast<size_t>(k)];
}

// Widens the separator: unknowns of side s coupled in A to side 1 − s join it, for the side
// that gives the smaller separator. The skeleton's separator is only as wide as its own edges;
// A's couplings reach further. Each coupling is read once, from its lower-triangle entry
// (u > v), and marks both ends.
void widen_separator(const SparseMatrix& a, const std::vector<int>& part, Scratch& s) {
  std::vector<int> crossing[2];
  for (int v : part) {
    const int side = s.side[static_cast<size_t>(v)];
    if (side == 2) continue;
    for (SparseMatrix::InnerIterator e(a, v); e; ++e) {
      const int u = static_cast<int>(e.row());
      if (u <= v || s.local[static_cast<size_t>(u)] < 0 || s.side[static_cast<size_t>(u)] != 1 - side) continue;
      for (const int end : {v, u})
        if (!s.crosses[static_cast<size_t>(end)]) {
          s.crosses[static_cast<size_t>(end)] = 1;
          crossing[s.side[static_cast<size_t>(end)]].push_back(end);
        }
    }
  }
  for (const auto& list : crossing)
    for (int v : list) s.crosses[static_cast<size_t>(v)] = 0;
  for (int v : crossing[crossing[0].size() <= crossing[1].size() ? 0 : 1]) s.side[static_cast<size_t>(v)] = 2;
}

// The part's two sides and its separator, by the sides written; resets the scratch.
std::array<Task, 3> split_by_side(const std::vector<int>& part, Scratch& s) {
  std::array<Task, 3> out{Task{}, Task{}, Task{{}, true}};
  for (int v : part) {
    out[static_cast<size_t>(s.side[static_cast<size_t>(v)])].unknowns.push_back(v);
    s.local[static_cast<size_t>(v)] = s.side[static_cast<size_t>(v)] = -1;
  }
  return out;
}

// Unknowns coupled to more than max(16, 10 √n) others (AMD's rule for dense rows): a feature's
// shared gradient (thesis §3.5) couples its anchor vertices to the whole feature. Dissecting with
// them in the parts splits them between the sides, and every feature vertex then couples across
// the separator: the 40K-band optimal merge's factors grew 15-fold. They are numbered last.
std::vector<char> dense_unknowns(const SparseMatrix& a) {
  const int n = static_cast<int>(a.cols());
  std::vector<int> degree(static_cast<size_t>(n), 0);
  for (int j = 0; j < n; ++j)
    for (SparseMatrix::InnerIterator e(a, j); e; ++e)
      if (e.row() > j) ++degree[static_cast<size_t>(j)], ++degree[static_cast<size_t>(e.row())];
  const double limit = std::max(16.0, 10.0 * std::sqrt(static_cast<double>(n)));
  std::vector<char> dense(static_cast<size_t>(n), 0);
  for (int v = 0; v < n; ++v) dense[static_cast<size_t>(v)] = degree[static_cast<size_t>(v)] > limit;
  return dense;
}

void require_skeleton_of(const SparseMatrix& A, const SparseMatrix& skeleton, const char* fn) {
  detail::require_square(A, fn);
  detail::require_square(skeleton, fn);
  if (skeleton.rows() != A.rows())
    throw InvalidArgument(std::string(fn) + ": skeleton is " + std::to_string(skeleton.rows()) + " by " +
                          std::to_string(skeleton.cols()) + ", the matrix " + std::to_string(A.rows()) + " by " +
                          std::to_string(A.cols()));
}

}  // namespace

std::vector<int> skeleton_nested_dissection(const SparseMatrix& A_in, const SparseMatrix& skeleton_in,
                                            SkeletonDissectionOptions options) {
  constexpr const char* fn = "solver::skeleton_nested_dissection()";
  require_skeleton_of(A_in, skeleton_in, fn);
  const SparseMatrix A = A_in.isCompressed() ? SparseMatrix() : SparseMatrix(A_in);
  const SparseMatrix& a = A_in.isCompressed() ? A_in : A;
  const int n = static_cast<int>(a.rows());
  if (n == 0) return {};
  const Adjacency g = symmetric_adjacency(skeleton_in);
  const int leaf = std::max(options.leaf_size, 2);

  detail::CholmodContext context;
  std::vector<int> component(static_cast<size_t>(n), -1);  // CAMD's constraint set of each unknown
  int components = 0;
  auto number_as_one = [&](const std::vector<int>& part) {
    if (part.empty()) return;
    for (int v : part) component[static_cast<size_t>(v)] = components;
    ++components;
  };
  Scratch scratch(n);
  // Depth first, the separator task below its two sides: every part is numbered before the
  // separators above it, the order CAMD's constraint sets must have.
  const std::vector<char> dense = dense_unknowns(a);
  std::vector<Task> stack;
  stack.push_back({{}, false});
  Task last{{}, true};
  for (int v = 0; v < n; ++v) (dense[static_cast<size_t>(v)] ? last : stack.back()).unknowns.push_back(v);
  while (!stack.empty()) {
    Task task = std::move(stack.back());
    stack.pop_back();
    if (task.separator || static_cast<int>(task.unknowns.size()) <= leaf) {
      number_as_one(task.unknowns);
      continue;
    }
    bisect_skeleton(g, task.unknowns, scratch, context, fn);
    widen_separator(a, task.unknowns, scratch);
    auto [left, right, separator] = split_by_side(task.unknowns, scratch);
    if (left.unknowns.empty() || right.unknowns.empty()) {
      number_as_one(task.unknowns);  // nothing to separate (a clique, or a failed bisection)
      continue;
    }
    stack.push_back(std::move(separator));
    stack.push_back(std::move(right));
    stack.push_back(std::move(left));
  }
  number_as_one(last.unknowns);

  std::vector<int> perm(static_cast<size_t>(n));
  cholmod_sparse view = detail::sparse_view(a, -1);
  cholmod_camd(&view, nullptr, 0, component.data(), perm.data(), context.get());
  context.check(fn, "cholmod_camd");
  return perm;
}

}  // namespace lapis::solver
