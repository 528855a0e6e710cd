// Local boundary refinement (thesis §2.5): a boundary condition made of few vertices leaves a
// large ROI extremely sensitive to each constraint, so a merging boundary that is short
// relative to the source is refined first.
#pragma once

#include <vector>

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

// Makes the faces next to each loop (vertex cycles along boundary loops) an annulus one ring
// wide, which a transition band (§3.3.3) needs at any width: where the mesh reaches from the
// loop back to itself within one triangle, the ring pinches. Splits, at their midpoints, the
// edges that join two vertices of one loop without being a loop edge, and the edges from a loop
// to a vertex that touches loops at separate places, until there are none (at most
// max_rounds rounds). The loops themselves and existing indices are unchanged; new vertices are
// appended. Returns the number of vertices added (0: the mesh was already fine).
int separate_loop_neighbourhoods(geometry::TriMesh& mesh, const std::vector<std::vector<int>>& loops,
                                 int max_rounds = 4);

}  // namespace lapis::mesh_merge
