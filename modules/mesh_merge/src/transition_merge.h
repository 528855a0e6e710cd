// Private: Poisson merging with overlapped transition regions (thesis §3.3.3), what
// Merger::merge() runs in MergeMode::Transition.
#pragma once

#include "lapis/mesh_merge/merge.h"

namespace lapis::mesh_merge::detail {

// source as given; options already checked. Fills every MergeResult field but the total time.
MergeResult merge_with_transition(const TriMesh& source, const TriMesh& target, const std::vector<LoopPair>& pairs,
                                  const MergeOptions& options);

}  // namespace lapis::mesh_merge::detail
