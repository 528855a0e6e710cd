// The salient feature files of `lapis features` and `lapis deform --features`, shared with
// the deform app:  {"features": [[v, v, ...], ...]}, each feature a list of vertex indices.
// And a PLY of the mesh with vertex colours by saliency, to look at what detection saw.
#pragma once

#include <filesystem>
#include <vector>

#include <Eigen/Core>

#include "lapis/geometry/tri_mesh.h"
#include "lapis/mesh_deform/salient_features.h"

namespace lapis::mesh_deform {

// Throws IoError naming the file (and the feature and entry) when it cannot be read or is
// malformed. Indices are not range-checked here (combine_features() does, with the mesh).
std::vector<Feature> read_features(const std::filesystem::path& path);
// Atomic; throws IoError.
void write_features(const std::filesystem::path& path, const std::vector<Feature>& features);

// ASCII PLY with per-vertex colours: saliency from blue (its minimum) through cyan, green and
// yellow to red (its maximum),
// feature vertices drawn white-tinted so the features stand out. Throws InvalidArgument when
// saliency has not one value per vertex, IoError when writing fails. Atomic.
void write_saliency_ply(const std::filesystem::path& path, const geometry::TriMesh& mesh,
                        const Eigen::VectorXd& saliency, const std::vector<Feature>& features);

}  // namespace lapis::mesh_deform
