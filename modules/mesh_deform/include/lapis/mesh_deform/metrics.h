// Distortion of a deformed mesh against its rest state, the figures tests, the CLI report and
// the benchmark compare methods by: edge length ratios, Laplacian-coordinate magnitude ratios
// (how well details keep their size, thesis §2.3), the ARAP energy (Sorkine & Alexa 2007) and
// per-triangle angle changes, each summarised as mean / max / 95th percentile.
#pragma once

#include <vector>

#include "lapis/geometry/tri_mesh.h"

namespace lapis::mesh_deform {

struct Summary {
  double mean = 0, max = 0, p95 = 0;
  int count = 0;
};

// Summary of values (empty: all zero).
Summary summarize(std::vector<double> values);

struct Distortion {
  Summary edge_length;       // |‖ẽ‖/‖e‖ − 1| per edge
  Summary laplacian_length;  // |‖δ̃_i‖/‖δ_i‖ − 1| per vertex with ‖δ_i‖ above 1e-8 of the mean
  Summary angle;             // |θ̃ − θ| in radians, per triangle corner
  // Σ_i Σ_j w⁺_ij ‖ẽ_ij − R_i e_ij‖² with the best rotation per vertex, divided by
  // Σ_i Σ_j w⁺_ij ‖e_ij‖² (0 for any rigid motion, scale free); w⁺_ij = ½ (max(0, cot α) +
  // max(0, cot β)), the weights ArapDeformer minimizes with (CGAL's ORIGINAL_ARAP weighting).
  double arap_energy = 0;
};

// rest, deformed  same faces, #V by 3 positions each. Cotangent weights on the rest mesh.
// Throws InvalidArgument "mesh_deform::distortion(): ..." when the vertex counts differ.
Distortion distortion(const geometry::TriMesh& rest, const geometry::Vertices& deformed);

}  // namespace lapis::mesh_deform
