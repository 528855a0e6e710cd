// Dividing curve (parting, thesis §4.5, Fig. 4.4): a curve on the scalp where hair parts
// and flows to both sides. At every unit point p a local frame {x, y, z}: y the scalp
// normal, z the curve tangent rotated about y by a tilt α interpolated from α0 to α1. In
// the local xy plane, on both sides of the y axis, constraints follow the tangents of a
// Gaussian (σ, h) through p at its inflexion point; discontinuity vectors of magnitude 0.3
// pointing away from the parting stop hair from growing across it.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "lapis/hair_field/constraints.h"
#include "lapis/hair_field/grid.h"
#include "lapis/hair_sketch/head.h"

namespace lapis::hair_sketch {

struct DividingCurve {
  std::vector<Eigen::Vector3d> points;  // polyline on (or near) the scalp
  double alpha0 = 0, alpha1 = 0;        // tilt angles (radians) at the start and end (Fig. 4.4)
  double sigma = 1.0;                   // Gaussian width, in grid spacings (Fig. 4.4 default)
  double height = 0.5;                  // Gaussian height h, in grid spacings (Fig. 4.4 default)
  double discontinuity = 0.3;           // magnitude of the discontinuity vectors (Fig. 4.4)
  int samples_per_side = 3;             // Gaussian-tangent constraints per side, 1 grid spacing apart

  // Throws InvalidArgument for a degenerate curve.
  std::vector<hair_field::Constraint> constraints(const hair_field::Grid& grid, const Head& head) const;
};

// The local frame's x axis (pointing to the +x side) at arc-length fraction s of the
// curve: what tests and the sketch layer use to tell the two sides apart.
Eigen::Vector3d dividing_side_axis(const DividingCurve& curve, const Head& head, double s);

}  // namespace lapis::hair_sketch
