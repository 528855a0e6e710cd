// Private: per-vertex neighbour lists with Laplacian edge weights in contiguous arrays (CSR),
// the layout every per-vertex loop of the deformers walks (ARAP's rotation fits, the implicit
// method's gradient stencils). Kept private because the loops want this exact memory layout;
// the geometry module's operators return sparse matrices instead.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "lapis/core/parallel_for.h"
#include "lapis/geometry/tri_mesh.h"
#include "lapis/mesh_deform/laplacian_weights.h"
#include "lapis/solver/types.h"

namespace lapis::mesh_deform::detail {

using geometry::TriMesh;
using geometry::Vertices;

// Neighbours of vertex i: nbr[offsets[i] .. offsets[i+1]), ascending, weight w_ij alongside, so that the
// Laplacian coordinate is δ_i = Σ_j w_ij (v_j − v_i) (thesis §2.3).
struct Stencil {
  std::vector<int> offsets;
  std::vector<int> nbr;
  std::vector<double> w;
  std::vector<char> boundary;  // #V: vertex lies on an open boundary
  int size() const { return static_cast<int>(offsets.size()) - 1; }
  int valence(int i) const { return offsets[i + 1] - offsets[i]; }
};

// What a cotangent weight takes from an obtuse angle, whose cotangent is negative. Laplacian
// coordinates need the signed cotangents (they are what make δ_i the mean-curvature normal);
// an energy Σ w_ij ‖·‖² needs non-negative weights, or it has no lower bound and minimizing it
// folds the mesh. ClampToZero is CGAL's ORIGINAL_ARAP weighting: ½ (max(0, cot α) + max(0, cot β)).
enum class ObtuseAngles { Keep, ClampToZero };

// Cotangent weights are libigl's 0.5 (cot α + cot β) (symmetric, unnormalized: the Voronoi
// area of §2.3 only reweights whole rows of the least-squares systems); uniform are 1/|N(i)|.
// P  positions to measure angles on (#V by 3), F faces.
Stencil make_stencil(const Vertices& P, const geometry::Faces& F, LaplacianWeights weights,
                     ObtuseAngles obtuse = ObtuseAngles::Keep);

// Recomputes only the weights of s for new positions P (same connectivity).
void reweight(Stencil& s, const Vertices& P, const geometry::Faces& F, LaplacianWeights weights,
              ObtuseAngles obtuse = ObtuseAngles::Keep);

// δ_i for every vertex (#V by 3).
Vertices laplacian_coordinates(const Stencil& s, const Vertices& P);

// Chunk of the per-frame and per-iteration vertex loops (core::parallel_for): the work per
// vertex varies (Newton steps in the rotation fits, valence), and on a shared machine one
// thread may lose its core for a while; whole chunks keep a thread's neighbour gathers local
// in a spatially ordered loop, at ~100 chunks per 100K vertices.
constexpr int kVertexChunk = 1024;

// f(k) for every k in [0, n), in chunks of kVertexChunk over core::parallel_for: a frame never
// waits for a thread that is not running.
template <class F>
void for_vertices(std::size_t n, F f) {
  core::parallel_for(0, static_cast<std::ptrdiff_t>(n), kVertexChunk, [&](std::ptrdiff_t lo, std::ptrdiff_t hi) {
    for (std::ptrdiff_t k = lo; k < hi; ++k) f(k);
  });
}

// Vertex order along a Morton (Z-order) curve through P's bounding box, as new index -> old:
// surface neighbours then lie close in memory, so a per-vertex loop's gathers of neighbour
// data hit the cache. Loop subdivision, for one, appends the edge midpoints, putting half of
// every vertex's neighbours #V/2 entries away.
std::vector<int> spatial_order(const Vertices& P);
// rank[order[k]] = k: each vertex's position in `order` (a permutation of 0 … n − 1).
std::vector<int> rank_in(const std::vector<int>& order);

// The mesh's edges as an n by n pattern (values 1): the skeleton on which the wide-stencil
// normal matrices are ordered (solver/ordering.h). Their columns couple vertices several rings
// apart, and METIS on that graph costs far more; the mesh's separators, widened, do nearly as
// well in a fraction of the time.
solver::SparseMatrix edge_graph(const Stencil& s);

// Mean edge length over the stencil's edges: the length scale that makes the soft weights of
// terms with different units (positions vs. deformation gradients) scale invariant.
double mean_edge_length(const Stencil& s, const Vertices& P);

}  // namespace lapis::mesh_deform::detail
