// Discrete Laplace operators and mass matrices as sparse matrices (Desbrun et al. 1999,
// Meyer et al. 2003): the building blocks of Laplacian editing (thesis ch. 2), Poisson
// merging (ch. 3) and the hair vector field (ch. 4).
//
// Sign convention (libigl's cotmatrix): L is symmetric negative semi-definite,
//   L_ij = 0.5 (cot alpha_ij + cot beta_ij) for an edge ij, L_ii = -sum_j L_ij,
// so (L x)_i = sum_j w_ij (x_j - x_i), and -L is the positive semi-definite stiffness.
#pragma once

#include <array>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "lapis/geometry/tri_mesh.h"

namespace lapis::geometry {

// A triangle is numerically degenerate when its smallest height is at most this fraction of its
// longest edge (is_thin_triangle, tri_mesh.h): a cap (an angle near 180 degrees) or a needle. Its cotangents are
// unbounded (a collinear triangle's come out ~1e16 from rounding), and squared in a least-squares normal matrix they
// swamp every other row: one such face made every deformer and the merge fail as "not positive definite". A triangle a
// million times longer than high has no usable angles. Looser than ValidationOptions::degenerate_tolerance (1e-14, zero
// area up to rounding): a face can have an area worth reporting and still angles no solver can use.
inline constexpr double kDegenerateTriangleHeight = 1e-6;

// Cotangents of the corner angles of the triangle (p0, p1, p2), cot[k] at p_k; all three zero
// for a degenerate triangle (see above) or a non-finite corner, which then contributes nothing
// to a Laplacian.
std::array<double, 3> triangle_cotangents(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                          const Eigen::Vector3d& p2);

// #V x #V cotangent Laplacian (convention above). Degenerate faces (kDegenerateTriangleHeight)
// contribute nothing. Columns are sorted, compressed.
Eigen::SparseMatrix<double> cotan_laplacian(const TriMesh& mesh);

// #V x #V graph Laplacian: L_ij = 1 for every edge, L_ii = -degree. Same sign convention.
Eigen::SparseMatrix<double> uniform_laplacian(const TriMesh& mesh);

enum class MassType {
  Barycentric,      // a third of each incident face's area
  Voronoi,          // Meyer et al. 2003 mixed Voronoi areas: Voronoi cells for non-obtuse
  Mixed = Voronoi,  // triangles, area/2 or area/4 split for obtuse ones (always positive)
};

// Per-vertex areas (the diagonal of mass_matrix); sums to the surface area.
Eigen::VectorXd vertex_areas(const TriMesh& mesh, MassType type = MassType::Voronoi);

// #V x #V diagonal (lumped) mass matrix of vertex_areas.
Eigen::SparseMatrix<double> mass_matrix(const TriMesh& mesh, MassType type = MassType::Voronoi);

// M^{-1} L: the area-normalized cotangent Laplacian, whose rows approximate the
// Laplace-Beltrami operator pointwise (M^{-1} L x = 2 H n on a surface, H mean curvature).
// Not symmetric. Throws InvalidArgument when a used vertex has zero area.
Eigen::SparseMatrix<double> normalized_cotan_laplacian(const TriMesh& mesh, MassType type = MassType::Voronoi);

// delta = L V: the Laplacian (differential) coordinates, #V x 3.
Eigen::MatrixX3d laplacian_coordinates(const Eigen::SparseMatrix<double>& L, const Vertices& V);
// The same with the cotangent Laplacian of mesh.
Eigen::MatrixX3d laplacian_coordinates(const TriMesh& mesh);

}  // namespace lapis::geometry
