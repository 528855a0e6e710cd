// Topology edits used by mesh merging (thesis ch. 3): cut away a band of faces, stitch the
// gap between two boundary polylines with a triangle strip, and weld vertices.
#pragma once

#include <utility>
#include <vector>

#include "lapis/geometry/tri_mesh.h"

namespace lapis::geometry {

// Removes faces (indices may repeat, any order) and then every vertex no face uses.
// vertex_map, when given, receives for each old vertex its new index or -1.
TriMesh remove_faces(const TriMesh& mesh, const std::vector<int>& faces, std::vector<int>* vertex_map = nullptr);

// The listed faces (in that order) over all of mesh's vertices, whose indices stay valid: a
// region as a mesh of its own, for its connectivity and boundary loops.
TriMesh with_faces(const TriMesh& mesh, const std::vector<int>& faces);

// The corners of the listed faces, ascending, each once; faces out of range are skipped.
std::vector<int> vertices_of_faces(const TriMesh& mesh, const std::vector<int>& faces);

// Splits each listed edge (vertex pairs in either order, repeats ignored) at its midpoint; a
// face with one, two or three split edges becomes two, three or four triangles of its winding.
// New vertices are appended in the order of `edges`, so existing indices stay valid. Returns the
// number of vertices added. Throws InvalidArgument, leaving the mesh as it was, for a pair that
// is not an edge of the mesh.
int split_edges(TriMesh& mesh, const std::vector<std::pair<int, int>>& edges);

// Drops vertices that no face uses; returns the old-to-new map (-1 for dropped ones).
std::vector<int> remove_unreferenced_vertices(TriMesh& mesh);

// Two faces sharing an edge whose normals are more than this apart fold onto each other (a
// spike or a notch), which no smooth surface has.
inline constexpr double kFoldedDihedralDeg = 120;

// Triangulates the band between polylines a and b (vertex indices into mesh.V) and appends
// the triangles to mesh.F: of the strips that advance along a and b (Fuchs, Kedem & Uselton
// 1977) and keep within 10 steps of the one with the shortest diagonals, the one with the
// fewest folded edges (against the faces already on a's and b's edges, and between its own
// triangles) and degenerate triangles, and among those the one with the shortest diagonals
// in total. (Without the bound, avoiding one fold could buy a fan reaching across the whole
// band.) O(|a|·|b|) time, 4·|a|·|b| bytes. With closed = true
// both are cycles and b is first rotated to start at its vertex nearest a[0]. The strip is
// oriented to match the existing faces on a's edges when there are any; otherwise it lies to
// the left of a walking forward, with b running the same way. Lengths within 1e-9
// (relative) of each other are ties, broken by position along the polylines (a's step
// first; b starts at the earliest of its nearest vertices), so a similarity of the mesh never
// changes the triangles. Returns the number of triangles added.
int bridge_polylines(TriMesh& mesh, const std::vector<int>& a, const std::vector<int>& b, bool closed);

// Triangulates the polygon through `polygon` (indices into V, in order, not repeating the
// first; planar or nearly so, like a triangle with vertices inserted along its sides): of all
// triangulations by diagonals, the one whose smallest angle is largest (Klincsek's O(k³)
// program; above 160 corners the best fan, O(k²)). Near-equal angles tie to the earlier
// corner, so a similarity of V does not change the result. Triangles keep the polygon's
// winding. Returns k − 2 triangles. Throws InvalidArgument for fewer than 3 corners or an index
// out of range.
Faces triangulate_polygon(const Vertices& V, const std::vector<int>& polygon);

// Merges every vertex within tolerance of another (grid hashing, transitively), keeps the
// lowest index's position, drops faces that collapse and unreferenced vertices. Returns the
// old-to-new vertex map.
std::vector<int> weld_vertices(TriMesh& mesh, double tolerance);

// Merges explicit pairs (first, second) into one vertex each, placed at their midpoint;
// collapsed faces and unused vertices are dropped. Returns the old-to-new vertex map.
std::vector<int> weld_vertex_pairs(TriMesh& mesh, const std::vector<std::pair<int, int>>& pairs);

}  // namespace lapis::geometry
