// Private: Poisson merging with overlapped transition regions (thesis §3.3.3), what
// Merger::merge() runs in MergeMode::Transition.
#pragma once

#include "lapis/mesh_merge/merge.h"

namespace lapis::mesh_merge::detail {

// §3.3.2: the source vertices within options.roi_width (0: the mean loop diameter) of its
// boundary loops, except options.handles. Throws InvalidArgument "mesh_merge::merge(): ..." for
// a handle on a loop.
std::vector<int> dependent_roi(const TriMesh& source, const Connectivity& conn, const MergeOptions& options);

// source as given; options already checked. Fills every MergeResult field but the total time.
MergeResult merge_with_transition(const TriMesh& source, const TriMesh& target, const std::vector<LoopPair>& pairs,
                                  const MergeOptions& options);

}  // namespace lapis::mesh_merge::detail
