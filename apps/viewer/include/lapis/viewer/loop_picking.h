// Picking curves that lie on surfaces (boundary loops, seams): the loop or loop vertex drawn
// nearest to a pixel, within a few pixels, skipping points the surfaces hide. Pure math on a
// camera, so apps and tests share it without a display.
#pragma once

#include <limits>
#include <vector>

#include "lapis/geometry/bvh.h"
#include "lapis/geometry/camera.h"

namespace lapis::viewer {

struct LoopPick {
  int loop = -1;                                            // index into the loops given, -1 for none
  int position = -1;                                        // index into that loop of the vertex nearest the pixel
  int vertex = -1;                                          // loops[loop][position]
  double pixels = std::numeric_limits<double>::infinity();  // screen distance to the loop
  explicit operator bool() const { return loop >= 0; }
};

// Whether world point p is visible from the camera: no surface of `occluders` crosses the ray
// from the eye before p (within a small fraction of the eye distance, so points on a surface
// count as visible).
bool visible(const geometry::CameraMatrices& camera, const Eigen::Vector3d& p,
             const std::vector<const geometry::Bvh*>& occluders);

// The closed loop (vertex cycles into V) passing nearest pixel (x, y), measured to its edges on
// screen, within max_pixels and visible there. `only` restricts the loops considered (empty:
// all).
LoopPick pick_loop(const geometry::CameraMatrices& camera, const geometry::Vertices& V,
                   const std::vector<std::vector<int>>& loops, double x, double y, double max_pixels,
                   const std::vector<const geometry::Bvh*>& occluders, const std::vector<int>& only = {});

// The visible loop vertex nearest pixel (x, y), within max_pixels (pixels = distance to it).
LoopPick pick_loop_vertex(const geometry::CameraMatrices& camera, const geometry::Vertices& V,
                          const std::vector<std::vector<int>>& loops, double x, double y, double max_pixels,
                          const std::vector<const geometry::Bvh*>& occluders, const std::vector<int>& only = {});

}  // namespace lapis::viewer
