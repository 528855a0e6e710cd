// A change of diagonal entries, A + Σ_t δ_t e_{s_t} e_{s_t}ᵀ with δ_t of either sign, applied to
// a simplicial LDLᵀ factor in place: the rank-1 updates (δ > 0) and downdates (δ < 0) of
// Method C1 (Gill, Golub, Murray & Saunders 1974, in the column-wise form of Davis & Hager's
// multiple-rank update) interleaved column by column over the union of their
// elimination-tree paths, in one sweep.
//
// Why not cholmod_updown: it takes one sign per call, so an edit that adds and removes
// constraints sweeps the shared top of the tree twice, and its scalar kernel spends one
// dependent multiply-add chain per term and entry. Here the rows of a column go four or eight
// at a time with AVX2/FMA (a column's row updates are independent; each carries its chain over
// the terms), the terms of both signs in one pass. Threads: the subtrees under the top
// separators are swept side by side (a term's path below the top stays in one subtree, and so
// do the workspace rows it writes), dealt by where this edit's terms start; then the rows of
// each shared ancestor are split over the threads. Used where the CPU has AVX2 and FMA
// (diagonal_updown_available()); elsewhere the caller keeps using cholmod_updown.
#pragma once

#include <cholmod.h>

#include <cstddef>
#include <utility>
#include <vector>

namespace lapis::solver::detail {

// Per-factor scratch, zero between calls: one dense column per term of a sweep, and per
// column of L the terms whose path passes it.
struct DiagonalUpdownWork {
  std::vector<double> w;           // 16 (terms per sweep) × n, term-major
  std::vector<unsigned> terms_at;  // n bit masks
  // Per column: the subtree (of the split of the elimination tree into whole subtrees,
  // tree_split.h) that holds it, or -1 for the shared ancestors; built on first use.
  std::vector<int> owner;
  std::vector<int> parent;  // the elimination tree, contiguous: paths are walked every call
  int units = 0;
  int threads = 0;
  long long pattern_entries = 0;  // Σ nnz of L's columns the split was made for
};

bool diagonal_updown_available();

// deltas: (permuted column s, δ) pairs, each column at most once. Returns -1, or the permuted
// column whose pivot would not stay positive; the factor is then partly modified and must be
// rebuilt by the caller.
std::ptrdiff_t diagonal_updown(cholmod_factor& L, const std::vector<std::pair<int, double>>& deltas,
                               DiagonalUpdownWork& work, int threads);

}  // namespace lapis::solver::detail
