// Least squares conformal maps (Lévy, Petitjean, Ray & Maillot 2002; the thesis' §3.4.2 reference
// [103]): a disk-like patch flattened so that each triangle's map is as close to a similarity as
// possible in the least-squares sense, with two vertices pinned. The optimal merging boundary
// (thesis §3.4) compares the band around a feature with the target region through these maps.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "lapis/geometry/tri_mesh.h"

namespace lapis::mesh_merge {

using geometry::TriMesh;

enum class ConformalWeights {
  // Lévy et al. §3.3: each face's two rows divided by √(2 A_T), so the energy is the integral of
  // |∂U/∂z̄|² over the surface, whatever the triangle sizes.
  PerArea,
  // The rows unscaled, as CGAL's LSCM_parameterizer_3 writes them ("no divide ... more
  // numerically stable in presence of degenerate triangles"): large faces weigh more.
  Unscaled,
};

// uv (#V by 2) minimizing Σ_T A_T ‖∂U/∂z̄‖² (the conformal energy of Lévy et al., Eq. 3) with
// uv(pins[0]) = at[0] and uv(pins[1]) = at[1]; vertices on no face get the pins' midpoint. The
// map keeps the faces' orientation (counter-clockwise faces stay counter-clockwise where the
// map does not fold). Through solver::LeastSquares (one factorization of the 2#V unknowns).
// Throws InvalidArgument "mesh_merge::lscm(): ..." for a pin out of range, equal pins or equal
// pin positions, and NotPositiveDefinite when the pins do not fix the map (a component with no
// pin).
Eigen::MatrixX2d lscm(const TriMesh& mesh, std::array<int, 2> pins, std::array<Eigen::Vector2d, 2> at,
                      ConformalWeights weights = ConformalWeights::PerArea);

// The two vertices of `loop` farthest apart in space (ties to the earlier pair): pinned at (0, 0)
// and (1, 0), they make lscm() invariant to a similarity of the mesh. Throws InvalidArgument for
// a loop of fewer than two vertices.
std::array<int, 2> farthest_pair(const TriMesh& mesh, const std::vector<int>& loop);

// lscm() pinned at the farthest pair of `loop`, scaled about the first pin so that the uv area
// equals the mesh's area (scale_to_area) or left with the pins at (0, 0) and (1, 0).
Eigen::MatrixX2d lscm_pinned_on_loop(const TriMesh& mesh, const std::vector<int>& loop, bool scale_to_area);

}  // namespace lapis::mesh_merge
