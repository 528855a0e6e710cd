// lapis-merge's first view, shared with the tests that click where the loops are on screen.
#pragma once

#include <algorithm>

#include "lapis/geometry/tri_mesh.h"
#include "lapis/viewer/orbit_camera.h"

namespace lapis::merge_app {

// Lapis' meshes are mostly z-up while the orbit camera keeps y up: look from the side and a
// little from above, so parts stacked along z lie side by side with their rims seen as ellipses.
constexpr double kViewYaw = 1.1, kViewPitch = 0.3;
// The panels take this many pixels on the right; the camera centres the meshes in the rest.
constexpr float kPanelWidth = 360;

// After OrbitCamera::frame(): back off so the framed scene fits the width left of the panels,
// and shift it into the middle of that part.
inline void fit_beside_panels(viewer::OrbitCamera& camera, int width, int height) {
  const double free = std::max(1.0, width - static_cast<double>(kPanelWidth));
  camera.distance *= std::max(1.0, static_cast<double>(width) / free);
  camera.far_plane = std::max(camera.far_plane, 4 * camera.distance);
  camera.pan(-0.5 * kPanelWidth, 0, height);
}

// MergeApp::on_start()'s camera computed off screen, for the tests and the demo generator that
// click where things land: the first view framed on the two meshes as placed.
inline viewer::OrbitCamera first_view_camera(const geometry::TriMesh& source, const geometry::TriMesh& target,
                                             int width, int height) {
  viewer::OrbitCamera camera;
  camera.yaw = kViewYaw, camera.pitch = kViewPitch;
  camera.frame(source.V.colwise().minCoeff().transpose().cwiseMin(target.V.colwise().minCoeff().transpose()),
               source.V.colwise().maxCoeff().transpose().cwiseMax(target.V.colwise().maxCoeff().transpose()));
  fit_beside_panels(camera, width, height);
  return camera;
}

}  // namespace lapis::merge_app
