// Mirroring a vertex selection across a plane (symmetry tools: paint one hand, select the
// other): each vertex's mirror image is matched to the nearest vertex of the mesh within a
// tolerance, since real meshes are only nearly symmetric and never share their vertices'
// positions exactly.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "lapis/geometry/tri_mesh.h"

namespace lapis::geometry {

struct MirroredVertices {
  std::vector<int> vertices;   // ascending: the matches of the mirrored vertices (each once)
  std::vector<int> unmatched;  // ascending: vertices of the set whose image has no vertex within the tolerance
};

// Reflects `set` across the plane through `point` with normal `normal` (any length) and
// matches each image to the nearest vertex of V no farther than `tolerance` from it (a
// bucket grid of cell `tolerance`, so a call costs O(#V) whatever the set). On a mesh
// symmetric about the plane, mirroring the result again gives the set back. Throws
// InvalidArgument for a vertex out of range, a zero or non-finite normal, a non-finite point
// or a tolerance that is not positive and finite.
MirroredVertices mirror_vertices(const Vertices& V, const std::vector<int>& set, const Eigen::Vector3d& point,
                                 const Eigen::Vector3d& normal, double tolerance);

}  // namespace lapis::geometry
