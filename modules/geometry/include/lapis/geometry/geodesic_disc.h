// The vertices within a geodesic radius of a vertex: a selection that follows the surface
// (a disc on a flat part, a cap on a finger) instead of the screen or a ball, which would
// jump across a gap to a neighbouring finger.
#pragma once

#include <vector>

#include "lapis/geometry/connectivity.h"
#include "lapis/geometry/tri_mesh.h"

namespace lapis::geometry {

// Vertices (ascending) whose distance from `seed` along mesh edges is at most `radius`.
// Distances are Dijkstra's over edge lengths, an upper bound of the geodesic distance: on an
// even triangulation it overestimates by a few percent (8% at most where every vertex has
// eight evenly spread edges), so the disc comes out slightly small along the directions no
// edge follows. That is what a selection tool needs: it costs only the selected vertices'
// edges (no solve, nothing precomputed per mesh, unlike the heat method), and its result is
// drawn at once, so the user sees the disc and sets the radius by eye. Throws
// InvalidArgument for a seed out of range or a radius that is negative or NaN.
std::vector<int> geodesic_disc(const TriMesh& mesh, const Connectivity& conn, int seed, double radius);

}  // namespace lapis::geometry
