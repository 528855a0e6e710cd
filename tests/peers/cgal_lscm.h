// CGAL's LSCM_parameterizer_3 (Surface_mesh_parameterization) behind a plain interface: the
// independent reference the mesh_merge tests check Lapis' least squares conformal map against.
#pragma once

#include <Eigen/Core>

#include "lapis/geometry/tri_mesh.h"

namespace lapis::peers {

// The conformal map of a disk-like mesh with `pin_a` at (0, 0.5) and `pin_b` at (1, 0.5), where
// CGAL's Two_vertices_parameterizer_3 puts given vertices. Throws std::runtime_error when CGAL
// reports an error.
Eigen::MatrixX2d cgal_lscm(const geometry::TriMesh& mesh, int pin_a, int pin_b);

}  // namespace lapis::peers
