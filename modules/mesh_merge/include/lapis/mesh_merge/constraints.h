// Boundary conditions of Poisson merging (thesis §3.3.1–3.3.2): for each source boundary
// vertex a position (its point on the target boundary) and a deformation gradient M_i = R_i S_i
// from local frames [tangent, normal, tangent x normal] at both ends, as one-vertex region
// handles of the implicit Laplacian deformer (thesis Eq. 2.8).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "lapis/mesh_deform/deformer.h"
#include "lapis/mesh_merge/boundary.h"

namespace lapis::mesh_merge {

struct BoundaryConstraint {
  int vertex = -1;                                               // source vertex
  Eigen::Vector3d position = Eigen::Vector3d::Zero();            // where it must go
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();        // R_i: source frame -> target frame
  double scale = 1.0;                                            // s_i: target / source tangent length
  Eigen::Matrix3d gradient() const { return scale * rotation; }  // M_i = R_i S_i
};

// Constraints of every source boundary vertex of every pair, pair by pair in loop order.
// Tangents are central differences along the loop (at the target: of the corresponding
// points, so s_i also measures how the correspondence stretches the boundary); normals are
// area-weighted vertex normals (at the target interpolated along the edge). keep_frames = true
// is configuration-dependent merging (§3.3.2): R_i = I, only positions and s_i change.
// Throws InvalidArgument "mesh_merge::boundary_constraints(): ..." when a frame is undefined
// (a zero tangent or a normal parallel to the tangent).
std::vector<BoundaryConstraint> boundary_constraints(const TriMesh& source, const TriMesh& target,
                                                     const std::vector<BoundaryCorrespondence>& pairs,
                                                     bool keep_frames);

// One one-vertex region handle per constraint, with the 4x4 that carries M_i and moves the
// vertex's rest position onto its target: T = [M_i | p_i − M_i v_i].
void add_region_handles(const TriMesh& source, const std::vector<BoundaryConstraint>& constraints,
                        mesh_deform::Selection& selection, mesh_deform::HandleTransforms& transforms);

}  // namespace lapis::mesh_merge
