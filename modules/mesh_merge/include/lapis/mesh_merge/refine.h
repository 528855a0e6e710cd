// Local boundary refinement (thesis §2.5): a boundary condition made of few vertices leaves a
// large ROI extremely sensitive to each constraint, so a merging boundary that is short
// relative to the source is refined first.
#pragma once

#include "lapis/geometry/tri_mesh.h"

namespace lapis::mesh_merge {

// Splits every boundary edge at its midpoint (its face becomes two triangles sharing the
// opposite vertex). New vertices are appended, so existing indices — the key vertices —
// stay valid. Returns the number of vertices added.
int split_boundary_edges(geometry::TriMesh& mesh);

// Repeats split_boundary_edges() while the boundary has fewer than min_ratio * sqrt(#V)
// vertices, at most max_levels times (a regular disc of n vertices has about 3.5 sqrt(n)).
// Returns the number of levels applied.
int refine_short_boundary(geometry::TriMesh& mesh, double min_ratio, int max_levels);

}  // namespace lapis::mesh_merge
