// Private: the triangles each isoline crosses, sampled under a budget (Au et al. 2007, §4.3),
// and the per-isoline fit of Eq. 8 from their normals, the only per-iteration work of Eq. 10
// besides one dense solve.
#pragma once

#include <vector>

#include <Eigen/Geometry>

#include "isoline_basis.h"
#include "lapis/mesh_deform/isolines.h"

namespace lapis::mesh_deform::detail {

// How r̂_{i,j} is fitted to the sampled triangles' normals (Eq. 8, weights l_k).
enum class NormalFit {
  Rotation,    // polar(Σ l_k² n_k n̄_kᵀ): defined for the coplanar normals of a bar's ring
  Similarity,  // the same rotation scaled by the isoline's length ratio Σ l'_k / Σ l_k
  Paper,       // Eq. 9: (Σ l_k² n_k n̄_kᵀ)(Σ l_k² n̄_k n̄_kᵀ)⁺, pseudo-inverse
};

struct IsolineSamples {
  std::vector<int> vertices;         // mesh vertices of the sampled triangles (the per-iteration set)
  std::vector<Eigen::Vector3i> tri;  // per sample: corners as indices into `vertices`
  std::vector<IsolineSegment> seg;   // per sample: its segment (face = mesh face)
  std::vector<Eigen::Vector3d> rest_normal;
  std::vector<int> offsets;  // samples of isoline ℓ: [offsets[ℓ], offsets[ℓ+1])
  std::vector<int> source;   // per isoline: the isoline whose fit it takes (itself if sampled)
  int crossed = 0;           // triangles crossed by all isolines before sampling
  // The sample vertices' interpolation data, copied out of the basis so that an iteration
  // reads a few contiguous kilobytes whatever #V: homogeneous rest positions, and K brackets each.
  std::vector<Eigen::Vector4d, Eigen::aligned_allocator<Eigen::Vector4d>> hom;
  std::vector<int> lower;
  std::vector<double> w0, w1;
  int size() const { return static_cast<int>(tri.size()); }
};

// budget  upper bound of n_tri over all isolines; min_per_isoline  the fewest an isoline keeps
// (when it crosses that many). faces  #F by 3; phi  #V by H.
IsolineSamples sample_isolines(const IsolineBasis& basis, const geometry::Faces& faces, const Eigen::MatrixXd& phi,
                               int budget, int min_per_isoline);

// Segments of every isoline of set i on the rest mesh (for display and tests): level j = isoline j.
std::vector<IsolineSegment> isoline_set_segments(const IsolineBasis& basis, const geometry::Faces& faces,
                                                 const Eigen::MatrixXd& phi, int set);

// Positions (normalized) of the sample vertices under R.
geometry::Vertices sample_positions(const IsolineSamples& samples, int sets, const TransformBlocks& R);

// r̂ per isoline (m 3×3 matrices) from the samples' positions X (#samples.vertices by 3, normalized).
// q  per isoline: the last fit's rotation, the start of the next (nearest_rotation).
void fit_isolines(const IsolineSamples& samples, const geometry::Vertices& X, NormalFit fit,
                  std::vector<Eigen::Quaterniond>& q, std::vector<Eigen::Matrix3d>& out);

}  // namespace lapis::mesh_deform::detail
