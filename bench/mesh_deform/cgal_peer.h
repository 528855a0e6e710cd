// The peer of the mesh_deform benchmark: CGAL's Surface_mesh_deformation with ORIGINAL_ARAP
// (Eigen SparseLU inside), behind a plain interface so CGAL stays in one translation unit.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "lapis/geometry/tri_mesh.h"

namespace lapis::bench {

struct PeerTiming {
  double setup_s = 0;           // ROI/control insertion + preprocess (factorization)
  double ms_per_iteration = 0;  // median over frames of frame time / iterations
  int frames = 0;
};

// Vertices outside roi are fixed; handle vertices are moved to T(frame) applied to their rest
// positions, frame by frame, with `iterations` ARAP iterations per frame (tolerance 0).
PeerTiming cgal_original_arap(const geometry::TriMesh& mesh, const std::vector<int>& roi, const std::vector<int>& handle,
                              const std::vector<Eigen::Matrix4d>& frames, int iterations);

}  // namespace lapis::bench
