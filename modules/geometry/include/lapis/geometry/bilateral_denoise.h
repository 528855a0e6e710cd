// Bilateral mesh denoising (Fleishman, Drori, Cohen-Or, "Bilateral mesh denoising", SIGGRAPH
// 2003): each vertex moves along its normal by a weighted mean of its neighbours' heights over
// its tangent plane, the weights falling off with distance (w_c, σ_c) and with the height
// itself (w_s, σ_s), so noise is removed while sharp features, whose heights are large, stay.
// Zhao et al. apply it before detecting salient features (§3.1).
#pragma once

#include "lapis/geometry/tri_mesh.h"

namespace lapis::geometry {

struct BilateralOptions {
  // Passes of the filter; Fleishman et al. iterate "a few times" (their results: 1–5).
  int iterations = 1;
  // σ_c, the spatial falloff; the neighbourhood is the vertices within 2σ_c reached along edges
  // (§3: "ρ = 2σ_c"). 0: the mean edge length, the scale of the noise Zhao et al. mean (the
  // paper leaves σ_c to the user, who picks it on the mesh).
  double sigma_c = 0;

  bool operator==(const BilateralOptions&) const = default;
};

// The denoised copy of `mesh` (same faces). σ_s is the standard deviation of the heights in
// each vertex's neighbourhood (§3, as Fleishman et al. choose it), with a floor of 1e-12 σ_c
// so a flat neighbourhood stays put. Boundary and isolated vertices move like the others
// (isolated ones have no neighbours and stay). Throws InvalidArgument for iterations < 0 or a
// σ_c that is negative or not finite.
TriMesh bilateral_denoise(const TriMesh& mesh, const BilateralOptions& options = {});

}  // namespace lapis::geometry
