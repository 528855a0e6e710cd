// Private: correspond_boundaries() without its input checks, for Merger, which checks its
// fixed source once (check_merge_source) and each target and pairs per merge
// (check_merge_pairs) instead of validating the whole source again on every re-merge.
#pragma once

#include <vector>

#include "lapis/mesh_merge/boundary.h"

namespace lapis::mesh_merge::detail {

// The input must have passed check_merge_input() (or its two parts).
std::vector<BoundaryCorrespondence> correspond_checked_boundaries(const TriMesh& source,
                                                                  const Connectivity& source_conn,
                                                                  const TriMesh& target,
                                                                  const Connectivity& target_conn,
                                                                  const std::vector<LoopPair>& pairs);

}  // namespace lapis::mesh_merge::detail
