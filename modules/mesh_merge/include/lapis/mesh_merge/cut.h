// Making merge inputs from whole meshes: cut a part off by a plane (a head off a body) or along
// the border of a painted region, with the maps back to the original vertices so key
// correspondences can be named on both parts.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "lapis/geometry/tri_mesh.h"

namespace lapis::mesh_merge {

struct PlaneCut {
  geometry::TriMesh above, below;  // faces whose centroid is on the normal's side / the other
  std::vector<int> above_to_mesh;  // new vertex -> original vertex
  std::vector<int> below_to_mesh;
};

// Splits mesh along its edges by the plane through `point` with `normal` (faces go by their
// centroid, so the cut loops are the edge paths nearest the plane). Only the largest
// connected component of each side is kept, so small islands do not add loops. Throws
// InvalidArgument "mesh_merge::cut_by_plane(): ..." for a zero normal or a side left empty.
PlaneCut cut_by_plane(const geometry::TriMesh& mesh, const Eigen::Vector3d& point, const Eigen::Vector3d& normal);

struct RegionCut {
  geometry::TriMesh inside, outside;  // faces with every corner in the region / the others
  std::vector<int> inside_to_mesh;    // new vertex -> original vertex
  std::vector<int> outside_to_mesh;
};

// Splits mesh along the border of a painted vertex region (the merge app's "cut a part off"):
// a face is inside when all three of its corners are selected, so the cut runs along mesh
// edges between the region's rim and the rest. The region is cleaned as a user means it: where
// the inside faces around a vertex form more than one fan (a painted rim touching itself) all
// faces around it go inside, so both parts stay manifold, and unpainted islands within the
// region (gaps a brush leaves) are filled, so a region painted as one patch gives one rim. As in
// cut_by_plane(), only the largest connected component of each side is kept. Throws InvalidArgument
// "mesh_merge::cut_by_region(): ..." for a vertex out of range or a side left empty.
RegionCut cut_by_region(const geometry::TriMesh& mesh, const std::vector<int>& region);

}  // namespace lapis::mesh_merge
