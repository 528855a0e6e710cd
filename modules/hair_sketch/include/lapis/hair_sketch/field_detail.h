// Local detail inside the field, thesis §4.7's second route: Eq. 4.1 rewritten as
//   E(t) = Σᵢ ||Δ(tᵢ) − δᵢ||² + ω² Σ_{i∈C} ||tᵢ − cᵢ||²,
// with δᵢ = Δ(tᵉᵢ) the differential coordinates of an example field tᵉ. Writing t = tᵉ + u
// turns E into the smooth energy of u with targets cᵢ − tᵉᵢ, so the existing solvers (and their
// incremental updates) solve it unchanged, and t = tᵉ + u: the example's local variation
// everywhere, the constraints where they are. StyleField does this when the settings ask for it.
#pragma once

#include <Eigen/Core>

#include "lapis/hair_field/grid.h"
#include "lapis/hair_field/grid_operators.h"

namespace lapis::hair_sketch {

// The bundled example: waves. The field swings around the vertical axis through `center`,
// tᵉ(p) = amplitude · sin(2π p_y / wavelength) · e_φ(p), e_φ the horizontal unit vector around
// the axis: along the head's circumference, across hair that falls down, alternating with height.
struct FieldDetailOptions {
  double amplitude = 0;     // 0: no detail (δᵢ ≡ 0, the thesis' Eq. 4.1)
  double wavelength = 0.5;  // in the head's units (the bundled head is about 2 tall)
};

// tᵉ on every grid node (num_nodes by 3). Throws InvalidArgument for a non-finite or negative
// amplitude or a wavelength that is not positive and finite.
hair_field::Field wavy_example_field(const hair_field::Grid& grid, const Eigen::Vector3d& center,
                                     const FieldDetailOptions& options);

}  // namespace lapis::hair_sketch
