// How rigidly a vertex set moved: the Kabsch fit behind Zhao et al.'s salient feature energy
// (Eq. 1) and the measure their claim is checked by (features "deform rigidly", §3.2).
#pragma once

#include <Eigen/Core>

#include "lapis/geometry/tri_mesh.h"
#include "lapis/mesh_deform/salient_features.h"

namespace lapis::mesh_deform {

// The rotation R minimising Σ_j ‖(p′_j − c′) − R (p_j − c)‖² over the feature's vertices (c, c′
// the centroids): the polar factor of A = Σ (p′_j − c′)(p_j − c)ᵀ, never a reflection. This is
// Eq. 1's exact minimiser; the paper's Müller-style polar(A·A_qq⁻¹) is not (spec §1.2).
Eigen::Matrix3d kabsch_rotation(const geometry::Vertices& rest, const geometry::Vertices& deformed, const Feature& f);

// √(E_F / |F|) / diameter of F at rest (its bounding box diagonal): 0 for a rigid motion of the
// feature, scale-free. Throws InvalidArgument for an empty feature or an index out of range.
double feature_rigidity_residual(const geometry::Vertices& rest, const geometry::Vertices& deformed, const Feature& f);

}  // namespace lapis::mesh_deform
