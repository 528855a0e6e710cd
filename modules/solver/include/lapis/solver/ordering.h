// Fill-reducing orderings for matrices whose graph is a wide neighbourhood of a sparse one.
//
// The implicit Laplacian's normal matrix (thesis Eq. 2.8) couples mesh vertices up to four
// rings apart (its 2-ring coherence pairs, §2.4.2, join two 1-ring stencils): ~60 entries per
// column. METIS on that graph spent a quarter of a one-off merge coarsening it (1.1 s of 4.3 s
// at 50K vertices). The separators it finds are bands a few rings wide across the mesh, and such
// bands can be found on the mesh's own 1-ring graph (the skeleton, ~7 entries per column) and
// widened until they also separate the dense graph: the factor comes out 4–8% larger than
// METIS's, in about a third of the ordering time (docs/decisions.md).
#pragma once

#include <vector>

#include "lapis/solver/types.h"

namespace lapis::solver {

struct SkeletonDissectionOptions {
  // Parts of at most this many unknowns are not dissected further: CAMD orders them (and
  // every separator) with the dense graph's exact fill, the parts before their separators.
  // 200–2000 differ by under 10% in factor flops; larger is faster to order.
  int leaf_size = 600;
};

// A fill-reducing ordering of the symmetric matrix A (perm[k] is the unknown eliminated
// k-th; A's lower triangle is read, the upper may be left out), by nested dissection of
// `skeleton`: each part is bisected on the skeleton (METIS'
// vertex separator through cholmod_bisect), the separator is widened by the vertices of one
// side that A couples to the other (the side that needs fewer), and the two sides recurse.
// Dense unknowns, coupled to more than max(16, 10 √n) others (AMD's rule), stay out of the
// dissection and are numbered last.
// skeleton  n by n, its pattern read (values and diagonal ignored, symmetric); any sparse
// graph in which A's couplings are short paths — the mesh's edges for a stencil matrix.
// The ordering is valid whatever the skeleton; it only decides the fill. Throws
// InvalidArgument if A or skeleton is not square or their sizes differ, SolverFailure if
// CHOLMOD fails.
std::vector<int> skeleton_nested_dissection(const SparseMatrix& A, const SparseMatrix& skeleton,
                                            SkeletonDissectionOptions options = {});

}  // namespace lapis::solver
