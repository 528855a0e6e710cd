#include "lapis/viewer/orbit_camera.h"

#include <algorithm>
#include <cmath>

namespace lapis::viewer {

OrbitCamera::OrbitCamera() = default;

void OrbitCamera::frame(const Eigen::Vector3d& box_min, const Eigen::Vector3d& box_max) {
  target = 0.5 * (box_min + box_max);
  const double radius = std::max(0.5 * (box_max - box_min).norm(), 1e-6);
  distance = radius / std::sin(0.5 * fov_y) * 1.05;
  near_plane = distance * 1e-3;
  far_plane = distance + 10 * radius;
}

void OrbitCamera::orbit(double dx, double dy) {
  yaw -= dx * 0.008;
  // Stop short of the poles so the up vector stays defined.
  pitch = std::clamp(pitch + dy * 0.008, -1.55, 1.55);
}

void OrbitCamera::pan(double dx, double dy, double viewport_height) {
  const Eigen::Matrix4d v = view();
  const Eigen::Vector3d right = v.block<1, 3>(0, 0).transpose();
  const Eigen::Vector3d up = v.block<1, 3>(1, 0).transpose();
  const double pixel = 2.0 * distance * std::tan(0.5 * fov_y) / std::max(viewport_height, 1.0);
  target += (-dx * right + dy * up) * pixel;
}

void OrbitCamera::zoom(double steps) {
  distance *= std::pow(0.9, steps);
  distance = std::clamp(distance, 1e-4, 1e6);
  far_plane = std::max(far_plane, 4 * distance);
}

Eigen::Vector3d OrbitCamera::eye() const {
  const Eigen::Vector3d dir(std::cos(pitch) * std::sin(yaw), std::sin(pitch), std::cos(pitch) * std::cos(yaw));
  return target + distance * dir;
}

Eigen::Matrix4d OrbitCamera::view() const {
  const Eigen::Vector3d e = eye();
  const Eigen::Vector3d f = (target - e).normalized();
  const Eigen::Vector3d r = f.cross(Eigen::Vector3d::UnitY()).normalized();
  const Eigen::Vector3d u = r.cross(f);
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.block<1, 3>(0, 0) = r.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -r.dot(e);
  m(1, 3) = -u.dot(e);
  m(2, 3) = f.dot(e);
  return m;
}

Eigen::Matrix4d OrbitCamera::projection(double aspect) const {
  const double t = 1.0 / std::tan(0.5 * fov_y);
  Eigen::Matrix4d p = Eigen::Matrix4d::Zero();
  p(0, 0) = t / aspect;
  p(1, 1) = t;
  p(2, 2) = -(far_plane + near_plane) / (far_plane - near_plane);
  p(2, 3) = -2.0 * far_plane * near_plane / (far_plane - near_plane);
  p(3, 2) = -1.0;
  return p;
}

CameraMatrices OrbitCamera::matrices(double width, double height) const {
  CameraMatrices c;
  c.view = view();
  c.projection = projection(width / std::max(height, 1.0));
  c.viewport = Eigen::Vector4d(0, 0, width, height);
  return c;
}

}  // namespace lapis::viewer
