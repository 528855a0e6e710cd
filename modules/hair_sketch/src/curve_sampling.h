// Polyline helpers shared by the style primitives: arc-length resampling at one grid
// spacing (thesis §4.5: "each segment is of the same length, set as the discretization
// size of the vector field") and the grid nodes a point constrains.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "lapis/hair_field/constraints.h"
#include "lapis/hair_field/grid.h"

namespace lapis::hair_sketch::detail {

// At most this many samples per curve: 2^20, about a thousand times a curve across the largest
// grid (1e9 unknowns, 1000 nodes a side).
constexpr double kMaxCurveSamples = 1 << 20;

// Points at arc length 0, h, 2h, ... (and the end point if the remainder is > h/2).
// Throws InvalidArgument (naming `who`) for fewer than 2 points, non-finite points, a
// zero-length polyline or h <= 0, ResourceLimit when it needs more than kMaxCurveSamples.
std::vector<Eigen::Vector3d> resample(const std::vector<Eigen::Vector3d>& polyline, double h, const char* who);

// Appends a constraint on each of the 8 corners of the grid cell containing p (those inside
// the grid): a segment's "neighbouring grid points". A p on a face, edge or node of the
// lattice (to rounding) constrains only that face's 4, edge's 2 or the 1 node.
void constrain_cell(const hair_field::Grid& grid, const Eigen::Vector3d& p, const Eigen::Vector3d& dir,
                    std::vector<hair_field::Constraint>& out);

// Appends a constraint on the grid node nearest p, if p is inside the grid.
void constrain_nearest(const hair_field::Grid& grid, const Eigen::Vector3d& p, const Eigen::Vector3d& dir,
                       std::vector<hair_field::Constraint>& out);

// Unit vectors u, v completing t to an orthonormal frame.
void orthonormal_frame(const Eigen::Vector3d& t, Eigen::Vector3d& u, Eigen::Vector3d& v);

}  // namespace lapis::hair_sketch::detail
