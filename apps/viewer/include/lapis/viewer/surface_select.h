// Painting vertex sets on a surface with the mouse: a brush (the vertices within a screen
// radius of the surface point under the cursor, grown through the mesh so it does not bleed
// through thin parts; or, x-ray, every vertex under the circle), a lasso (the visible vertices
// inside a screen polygon, occlusion tested through the BVH; or, x-ray, all of them), and
// ring-wise grow / shrink of a set. The apps keep the sets;
// these functions only compute them, so tests drive them with synthetic cameras.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "lapis/geometry/bvh.h"
#include "lapis/geometry/camera.h"
#include "lapis/geometry/connectivity.h"
#include "lapis/geometry/tri_mesh.h"

namespace lapis::viewer {

struct BrushOptions {
  double radius_px = 20;  // brush radius on screen, turned into world units at the hit depth
  // X-ray: every vertex in front of the camera whose projection lies within radius_px of the
  // pixel, hidden or not (Blender's circle select with x-ray on), so a stroke over a hand
  // paints its back too. The surface need not be under the pixel.
  bool through = false;
};

// Vertices (ascending) within the brush's world radius of the surface point under `pixel`,
// reached from the hit face through mesh edges without leaving the ball. Empty when the
// pixel misses the surface. With `through`, the vertices under the screen circle instead.
// `bvh` and `conn` must be built on `mesh` (its current positions).
std::vector<int> brush_vertices(const geometry::TriMesh& mesh, const geometry::Connectivity& conn,
                                const geometry::Bvh& bvh, const geometry::CameraMatrices& camera,
                                const Eigen::Vector2d& pixel, const BrushOptions& options = {});

// Even-odd rule; a polygon with fewer than three points contains nothing. The last point
// connects back to the first.
bool point_in_polygon(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& p);

struct LassoOptions {
  // Only vertices facing the camera and not hidden behind the surface (a BVH ray per
  // candidate), as a user expects of a lasso drawn over what they see.
  bool visible_only = true;
};

// Vertices (ascending) whose projection lies inside the lasso polygon (pixels, y down) and
// in front of the camera; with visible_only, only those the camera sees.
std::vector<int> lasso_vertices(const geometry::TriMesh& mesh, const geometry::Bvh& bvh,
                                const geometry::CameraMatrices& camera, const std::vector<Eigen::Vector2d>& polygon,
                                const LassoOptions& options = {});

// `set` plus every vertex within `rings` edges of it (ascending).
std::vector<int> grow_rings(const geometry::Connectivity& conn, const std::vector<int>& set, int rings);
// `set` minus every vertex within `rings` edges of a vertex outside it (ascending): the
// inverse of grow_rings on a set's interior.
std::vector<int> shrink_rings(const geometry::Connectivity& conn, const std::vector<int>& set, int rings);

}  // namespace lapis::viewer
