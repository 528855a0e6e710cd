// The apps' camera: orbits a target point (right-drag), pans (middle-drag), zooms (wheel),
// frames a bounding box. Pure math on Eigen, no GL: modules and tests use its matrices
// (view, projection, viewport) to turn screen strokes into rays.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "lapis/geometry/camera.h"

namespace lapis::viewer {

using geometry::CameraMatrices;
using geometry::Ray;

class OrbitCamera {
 public:
  OrbitCamera();

  // Fits the box into view from the current direction.
  void frame(const Eigen::Vector3d& box_min, const Eigen::Vector3d& box_max);
  // Screen-space drags in pixels.
  void orbit(double dx, double dy);
  void pan(double dx, double dy, double viewport_height);
  // Positive steps move closer.
  void zoom(double steps);

  Eigen::Vector3d eye() const;
  Eigen::Matrix4d view() const;
  Eigen::Matrix4d projection(double aspect) const;
  CameraMatrices matrices(double width, double height) const;

  // Setters for exact placement (sessions store them).
  double yaw = 0.0, pitch = 0.15, distance = 3.0, fov_y = 0.7;  // radians
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  double near_plane = 0.01, far_plane = 100.0;
};

}  // namespace lapis::viewer
