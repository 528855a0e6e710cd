// Helpers shared by the sketch interpretation files: stroke validation and messages.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "lapis/hair_sketch/sketch.h"

namespace lapis::hair_sketch::detail {

[[noreturn]] inline void reject(const char* fn, const std::string& reason) {
  throw StrokeRejected(std::string(fn) + ": " + reason);
}

// Rejects strokes with fewer than 2 points, non-finite points or a screen arc length below
// options.min_stroke_pixels.
void check_stroke(const Stroke& stroke, const SketchOptions& options, const char* fn);

// Arc length of a polyline.
double polyline_length(const std::vector<Eigen::Vector3d>& p);

}  // namespace lapis::hair_sketch::detail
