// Picking: the surface point under a pixel, by casting the camera ray into a BVH.
#pragma once

#include <optional>

#include "lapis/geometry/bvh.h"
#include "lapis/geometry/camera.h"

namespace lapis::viewer {

inline std::optional<geometry::RayHit> pick(const geometry::Bvh& bvh, const geometry::CameraMatrices& camera, double x,
                                            double y) {
  const geometry::Ray ray = geometry::unproject_ray(camera, x, y);
  return bvh.intersect(ray.origin, ray.direction);
}

// The corner of the hit face nearest to the hit point (vertex picking).
inline int nearest_corner(const geometry::TriMesh& mesh, const geometry::RayHit& hit) {
  int best = 0;
  for (int k = 1; k < 3; ++k)
    if (hit.barycentric[k] > hit.barycentric[best]) best = k;
  return mesh.F(hit.face, best);
}

}  // namespace lapis::viewer
