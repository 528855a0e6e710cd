// Handle-aware harmonic fields (Au et al. 2007, §4.1): one scalar field per handle, 1 on it
// and 0 on the others, harmonic (cotangent Laplacian) elsewhere, so that the fields form a
// partition of unity (footnote 1). The fixed region outside the ROI counts as a handle. Their
// gradient magnitude is the handle-aware rigidity ψ the deform app shows (§4.1, Fig. 3–4).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "lapis/mesh_deform/deformer.h"

namespace lapis::mesh_deform {

struct HandleFieldOptions {
  // A point handle's field is 1 on a geodesic disc of this radius (of the bounding-box
  // diagonal) around it, not on the vertex alone: a one-vertex Dirichlet value decays as the
  // mesh is refined, so the isolines would depend on the sampling (§5, Fig. 8). The vertex's
  // 1-ring is always in the disc.
  double point_handle_radius = 0.02;

  bool operator==(const HandleFieldOptions&) const = default;
};

// The Dirichlet sets: column h of the fields is 1 on handle_vertices[h]. Column 0 is the fixed
// region when the ROI leaves one, then the region handles, then the point handles' discs.
struct HandleSets {
  std::vector<std::vector<int>> handle_vertices;
  bool has_fixed_region = false;
  int column_of_region(int h) const { return (has_fixed_region ? 1 : 0) + h; }
  int column_of_point(int h, int num_regions) const { return column_of_region(num_regions) + h; }
  int size() const { return static_cast<int>(handle_vertices.size()); }
};

// A disc takes only free vertices no earlier disc took. Throws InvalidArgument
// "mesh_deform::handle_sets(): ..." when fewer than two handles result (the fixed region counts).
HandleSets handle_sets(const TriMesh& mesh, const Layout& layout, const Selection& selection,
                       const HandleFieldOptions& options = {});

struct HandleFields {
  Eigen::MatrixXd phi;       // #V by H; rows sum to 1, entries in [0, 1]
  double overshoot = 0;      // largest distance of a solved value outside [0, 1] before clamping
  double residual = 0;       // max |(L φ_h)_i| over free vertices i, relative to max |L_ii|
  long long factor_nnz = 0;  // of the one Cholesky factor of −L_ff
  double factorize_ms = 0;
  double solve_ms = 0;
};

// Solves L φ_h = 0 on the vertices outside every set with one factorization of −L_ff and H − 1
// right-hand sides; the last field is 1 − Σ of the others, so the partition of unity holds by
// construction and `residual` measures it. Values outside [0, 1] (obtuse triangles, point
// handles; §5 "overflow") are clamped and each row renormalized; `overshoot` reports them.
// Throws InvalidArgument "mesh_deform::harmonic_fields(): ..." naming a vertex of a connected
// component that holds no handle vertex (its field is undefined).
HandleFields harmonic_fields(const TriMesh& mesh, const HandleSets& sets);

// ψ = sqrt(Σ_h ‖∇φ_h‖²) per vertex (area-weighted mean of its faces' gradients), #V: the
// handle-aware rigidity of §4.1, small where the shape moves rigidly.
Eigen::VectorXd handle_rigidity(const TriMesh& mesh, const Eigen::MatrixXd& phi);

}  // namespace lapis::mesh_deform
