// Merging boundaries (thesis §3.3.1): which source loop meets which target loop, checked for
// the mistakes a user makes, and the arc-length correspondence between key vertices that
// gives every source boundary vertex its position on the target boundary.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "lapis/core/error.h"
#include "lapis/geometry/connectivity.h"
#include "lapis/geometry/tri_mesh.h"

namespace lapis::mesh_merge {

using geometry::Connectivity;
using geometry::TriMesh;
using geometry::Vertices;

// A user's key vertex correspondence: a source boundary vertex and the target boundary vertex
// it must land on.
struct KeyCorrespondence {
  int source = -1;
  int target = -1;
};

// One merging-boundary pair, named by its key correspondences (at least one; more pin the
// parameterization down). All keys of a pair lie on one source loop and one target loop, in
// the same cyclic order along both (source forward, target backward: the seam's two sides).
struct LoopPair {
  std::vector<KeyCorrespondence> keys;
};

// A resolved pair. source_loop runs with the source surface on its left and starts at the
// first key; target_loop runs against the target's face orientation (so it advances in the
// same direction as source_loop once merged) and starts at the first key's target vertex.
struct BoundaryCorrespondence {
  std::vector<int> source_loop;
  std::vector<int> target_loop;
  // For source_loop[i]: the point at parameter target_t[i] in [0, 1) along the target edge
  // (target_loop[target_edge[i]], target_loop[target_edge[i] + 1 mod n]).
  std::vector<int> target_edge;
  std::vector<double> target_t;
  Vertices target_points;  // #source_loop by 3
};

// Checks the input of a merge and throws InvalidArgument "mesh_merge::check_merge_input(): ..."
// for: a source without boundary (closed), a non-manifold source or target near the boundary
// (non-manifold edges or vertices), pair and loop counts that differ (every source loop must be
// merged exactly once), a pair without keys, a key vertex out of range or not on a boundary
// loop, keys of one pair on different loops, two pairs sharing a loop, and keys whose cyclic
// order differs between the two loops.
void check_merge_input(const TriMesh& source, const Connectivity& source_conn, const TriMesh& target,
                       const Connectivity& target_conn, const std::vector<LoopPair>& pairs);

// The part of check_merge_input() that needs the source only (closed, non-manifold), with
// the same messages.
void check_merge_source(const TriMesh& source, const Connectivity& source_conn);
// The rest of check_merge_input(): the target and the pairs, for a source that passed
// check_merge_source() (Merger checks its source once and each target and pairs per merge:
// validating a 50K-vertex source twice on every re-merge cost about what the solves did,
// 84 of 259 ms).
void check_merge_pairs(const TriMesh& source, const Connectivity& source_conn, const TriMesh& target,
                       const Connectivity& target_conn, const std::vector<LoopPair>& pairs);

// Arc-length curve parameterization between consecutive keys (thesis §3.3.1): a source vertex
// a fraction f along the source arc from key k to key k+1 goes to the point a fraction f
// along the target arc between the same keys. With one key the whole loop is one arc.
// Calls check_merge_input() first.
std::vector<BoundaryCorrespondence> correspond_boundaries(const TriMesh& source, const Connectivity& source_conn,
                                                          const TriMesh& target, const Connectivity& target_conn,
                                                          const std::vector<LoopPair>& pairs);

// Length of the closed polyline through V's rows `loop` (the closing edge included).
double loop_perimeter(const Vertices& V, const std::vector<int>& loop);

}  // namespace lapis::mesh_merge
