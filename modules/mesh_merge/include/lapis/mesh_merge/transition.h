// Overlapped transition regions of Poisson mesh merging (thesis §3.3.3): the band of each mesh
// next to its merging loop (edge-path distance below a width), cut open along a shortest path
// from the key vertex across the band and parameterized over the unit square, and the map of
// one band's vertices into the other band's triangles (barycentric weights b_i1..b_i3).
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "lapis/mesh_merge/boundary.h"

namespace lapis::mesh_merge {

// A band cut open and parameterized over [0,1]²: u runs along the merging loop (the loop's
// given parameters) and along the rim (normalized arc length from the cut), v = 0 on the loop
// and 1 on the rim; inside, each vertex is the mean of its neighbours (Tutte's embedding with
// those boundary values: one-to-one because the square is convex).
struct TransitionBand {
  std::vector<int> loop;  // the merging loop in the seam's direction (as given), loop[0] = the key
  std::vector<int> rim;   // the band's inner border (kept, outside the band), same direction, rim[0] = the cut's end
  std::vector<int> vertices;  // the band: every vertex of `faces` that is not on the rim, ascending
  std::vector<int> faces;     // faces with a vertex closer to the loop than the width
  std::vector<int> cut;       // loop[0] ... rim[0]: the shortest path the band is cut along
  // The cut-open band: vertex k of the parameter domain is mesh vertex param_vertex[k] at
  // uv.row(k); vertices on the cut appear twice (u = 0 and u = 1).
  std::vector<int> param_vertex;
  Eigen::MatrixX2d uv;
  geometry::Faces param_faces;  // `faces` in parameter-domain indices
  std::vector<int> param_of;  // #V: a parameter-domain index of each band and rim vertex (the u = 0 copy), -1 elsewhere
  Eigen::Vector2d at(int vertex) const { return uv.row(param_of[vertex]).transpose(); }
};

// The band of `mesh` next to `loop` (a boundary loop, in either direction; reversed = true when
// it runs against the faces' orientation, as a BoundaryCorrespondence's target_loop does).
// loop_u  #loop parameters in [0, 1), increasing, loop_u[0] = 0: where the other mesh's loop
// meets this one (so that key correspondences get the same u on both bands).
// Throws InvalidArgument "mesh_merge::transition_band(): ..." (naming `which`, e.g. "source")
// for width <= 0 or not finite, mismatched sizes, a band that covers the whole mesh, and a band
// that is not an annulus between the loop and one inner rim (it reaches another boundary, wraps
// around a handle or pinches), or that cannot be cut from loop[0] to the rim.
TransitionBand transition_band(const TriMesh& mesh, const Connectivity& conn, const std::vector<int>& loop,
                               const std::vector<double>& loop_u, double width, bool reversed, const char* which);

// Whether transition_band() would accept this band: it leaves part of the mesh uncovered, is an
// annulus between the loop and one inner rim, and can be cut from loop[0] to the rim. When it
// would not, writes transition_band()'s message (naming `which`) to *why, if given. Builds no
// parameterization.
bool band_is_annulus(const TriMesh& mesh, const Connectivity& conn, const std::vector<int>& loop, double width,
                     const char* which, std::string* why = nullptr);

// A point of a band as a barycentric combination of three mesh vertices.
struct BandPoint {
  std::array<int, 3> vertices{-1, -1, -1};
  std::array<double, 3> weights{0, 0, 0};
};

// Where each of `from`'s vertices lies on `to` when the two bands overlap (§3.3.3): the source
// band's loop lies on the target band's rim and vice versa, so (u, v) on one band is (u, 1 − v)
// on the other. Parallel to from.vertices. Points that fall outside every triangle (rounding
// at the square's edges) take the nearest triangle's clamped weights.
std::vector<BandPoint> overlap_points(const TransitionBand& from, const TransitionBand& to);

// Normalized cumulative arc length of a closed polyline: 0 at loop[0], increasing, < 1.
std::vector<double> arc_length_params(const Vertices& V, const std::vector<int>& loop);

}  // namespace lapis::mesh_merge
