// Cutting an annulus open along a path across it, so that the band becomes a disk and each cut
// vertex gets a twin: the transition bands (§3.3.3) are parameterized over a square this way, and
// the optimal boundary (§3.4.3) searches closed paths as paths from a cut vertex to its twin.
#pragma once

#include <vector>

#include "lapis/geometry/connectivity.h"

namespace lapis::mesh_merge::detail {

struct CutOpen {
  // The faces, with each cut vertex cut[k] replaced by its twin num_vertices + k in the faces on
  // the path's upper side (its left seen along the loop when reversed = false, its right when
  // reversed = true).
  geometry::Faces faces;
  int failed_at = -1;  // a cut vertex whose faces do not form one fan split in two by the path; faces is then empty
};

// conn  connectivity of (V, F); cut  a path of vertices whose ends lie on the border (its inner
// vertices off it), as a shortest path across a band is.
CutOpen cut_open(const geometry::Connectivity& conn, const geometry::Faces& F, const std::vector<int>& cut,
                 bool reversed);

}  // namespace lapis::mesh_merge::detail
