// Private: the start of a cold frame for the local–global methods (ARAP, salient features):
// every vertex turned by the blend of the region handles' rotation vectors, weighted by a
// field that is 1 on a handle and 0 on the fixed region. Where the weights of every vertex sum
// to one and all handles share one rotation, every vertex starts with that rotation, so the
// first global step reproduces a rigid motion shared by all handles.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "lapis/mesh_deform/deformer.h"

namespace lapis::mesh_deform::detail {

// The rotation vector (axis · angle, angle in [0, π]) of each region handle's transform (the
// rotation factor of its linear part, so a scaled handle turns by its rotation alone).
std::vector<Eigen::Vector3d> region_rotation_vectors(const HandleTransforms& transforms);

// The log of each region handle's uniform scale, ln ∛|det L| of its linear part L: blended
// like the rotation vectors where a method models scale.
Eigen::VectorXd region_log_scales(const HandleTransforms& transforms);

// One row of a per-vertex weight matrix, taken where it lies: a row of a column-major matrix is
// strided, and a contiguous Ref would copy it to the heap for every vertex of every cold frame.
using RowWeights = Eigen::Ref<const Eigen::RowVectorXd, 0, Eigen::InnerStride<>>;

// The rotation by Σ_h weights(h) r_h (point handles and the fixed region count as the identity).
Eigen::Quaterniond blended_rotation(const RowWeights& weights, const std::vector<Eigen::Vector3d>& r);

}  // namespace lapis::mesh_deform::detail
