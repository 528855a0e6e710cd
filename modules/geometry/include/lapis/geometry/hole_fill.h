// Filling a hole bounded by one closed polyline with triangles of least total area (Barequet &
// Sharir 1995; the "minimal total area" fill of thesis §3.4.2, its reference [104]): the optimal
// merging boundary parameterizes the band around a feature with the feature replaced by this fill,
// so that the feature may have any genus.
#pragma once

#include <vector>

#include "lapis/geometry/tri_mesh.h"

namespace lapis::geometry {

struct HoleFill {
  Faces faces;       // indices into V, then V.rows() + i for added.row(i)
  Vertices added;    // the centroid of a fan fill; empty for the area-minimal fill
  double area = 0;   // total area of `faces`
  bool fan = false;  // the loop was longer than max_exact_corners: a centroid fan instead
};

// loop  a hole's vertices in order (not repeating the first), running the way the surrounding
// faces' half-edges do along it (a Connectivity::boundary_loops() loop), so the fill's faces,
// which run against it, continue the surface's orientation.
// Of all triangulations of the polygon by its diagonals, the one of least total area (dynamic
// programming over sub-polygons: O(k³) time, O(k²) memory); area ties go to the earlier split
// corner, so a similarity of V does not change the result. Above max_exact_corners corners (a
// second at about 1000), a fan around the loop's centroid. Returns k − 2 faces (k with a fan).
// Throws InvalidArgument for fewer than 3 corners, a repeated corner or an index out of range.
HoleFill minimal_area_fill(const Vertices& V, const std::vector<int>& loop, int max_exact_corners = 1000);

}  // namespace lapis::geometry
