// Private: the Laplacian nodes of the edge-based method and of its vertex-based baseline in
// one form, so that the operator, the cells and the transform fits are written once. A node's
// cell is the vectors e = c (v_p − v_q) to its neighbours (Wang et al. §3.4), and its
// Laplacian vector is δ = Σ ω e (Eq. 1, the paper's sign), a linear function of the vertices.
#pragma once

#include <array>
#include <vector>

#include "lapis/geometry/tri_mesh.h"
#include "lapis/mesh_deform/laplacian_weights.h"
#include "lapis/solver/types.h"

namespace lapis::mesh_deform::detail {

struct LaplacianCells {
  double c = 1;                          // e = c (v_p − v_q): 1 between vertices, ½ between edge midpoints
  std::vector<int> offsets;              // node a's cell: entries [offsets[a], offsets[a+1])
  std::vector<int> p, q;                 // per entry: the two vertices of e
  std::vector<double> w;                 // per entry: ω, signed (cotangent weights may be negative)
  std::vector<std::array<int, 2>> ends;  // edge domain, per node: its edge (i, j), i < j
  int num_nodes() const { return static_cast<int>(offsets.size()) - 1; }
};

struct Stencil;

// §3.1 Eq. 1: one node per vertex, its 1-ring as the cell (e = v_i − v_j), weights the
// stencil's (uniform 1/|N(i)| or cotangent).
LaplacianCells vertex_cells(const Stencil& s);

// §3.3: one node per edge (i, j), i < j, at its midpoint; the cell joins it to the midpoints
// of every other edge at i or j: m_ij − m_ik = (v_j − v_k)/2. Uniform: ω = 1/|N(ij)|;
// cotangent: each neighbouring edge carries its own cotangent weight from s (the paper gives
// none).
LaplacianCells edge_cells(const Stencil& s, LaplacianWeights weights);

// The rows of D (δ_a = D_a V) for the given nodes, #nodes by #V.
solver::SparseMatrix laplacian_rows(const LaplacianCells& cells, const std::vector<int>& nodes, int num_vertices);

// δ_a at positions P for every node (#nodes by 3).
geometry::Vertices laplacian_vectors(const LaplacianCells& cells, const geometry::Vertices& P);

}  // namespace lapis::mesh_deform::detail
