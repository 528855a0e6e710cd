// Scalar fields as vertex colours (distortion, seam quality): a perceptually ordered map from
// dark blue through teal and yellow to red, and the robust range apps put in their legends.
#pragma once

#include <Eigen/Core>

#include "lapis/viewer/scene.h"

namespace lapis::viewer {

// Colour of t in [0, 1] (clamped; NaN maps to grey).
Eigen::Vector3f colormap(double t);

// Per-value colours of (values − lo) / (hi − lo); hi <= lo maps everything to colormap(0).
Points3f colorize(const Eigen::VectorXd& values, double lo, double hi);

// The value below which `fraction` of the finite values lie (0 for none): legends use the
// 95th percentile so one spike does not wash the map out.
double percentile(const Eigen::VectorXd& values, double fraction);

}  // namespace lapis::viewer
