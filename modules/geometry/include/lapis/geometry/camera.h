// A pinhole camera as the apps and the sketching code see it: view and projection matrices
// (OpenGL conventions) and a viewport in pixels with y growing downward, as mouse events
// report it. Projection and unprojection are pure functions, so every interaction that
// starts from screen points is testable without a window.
#pragma once

#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/LU>

namespace lapis::geometry {

struct CameraMatrices {
  Eigen::Matrix4d view = Eigen::Matrix4d::Identity();
  Eigen::Matrix4d projection = Eigen::Matrix4d::Identity();
  Eigen::Vector4d viewport{0, 0, 1, 1};  // x, y, width, height in pixels; y grows downward
};

struct Ray {
  Eigen::Vector3d origin;
  Eigen::Vector3d direction;  // unit length
};

// Pixel coordinates (y down) and window depth in [0, 1] of a world point.
inline Eigen::Vector3d project(const CameraMatrices& camera, const Eigen::Vector3d& world) {
  const Eigen::Vector4d clip = camera.projection * camera.view * world.homogeneous();
  const Eigen::Vector3d ndc = clip.head<3>() / clip.w();
  const auto& vp = camera.viewport;
  return {vp[0] + (ndc.x() + 1) * 0.5 * vp[2], vp[1] + (1 - ndc.y()) * 0.5 * vp[3], (ndc.z() + 1) * 0.5};
}

// The world point at pixel (x, y) (y down) and window depth in [0, 1].
inline Eigen::Vector3d unproject(const CameraMatrices& camera, double x, double y, double depth) {
  const auto& vp = camera.viewport;
  const Eigen::Vector4d ndc(2 * (x - vp[0]) / vp[2] - 1, 1 - 2 * (y - vp[1]) / vp[3], 2 * depth - 1, 1);
  const Eigen::Vector4d w = (camera.projection * camera.view).inverse() * ndc;
  return w.head<3>() / w.w();
}

// The ray from the near plane through pixel (x, y).
inline Ray unproject_ray(const CameraMatrices& camera, double x, double y) {
  const Eigen::Vector3d p0 = unproject(camera, x, y, 0.0), p1 = unproject(camera, x, y, 1.0);
  return {p0, (p1 - p0).normalized()};
}

// The eye position (camera centre) in world coordinates.
inline Eigen::Vector3d eye_position(const CameraMatrices& camera) {
  return -camera.view.block<3, 3>(0, 0).transpose() * camera.view.block<3, 1>(0, 3);
}

}  // namespace lapis::geometry

namespace lapis::geometry {

// A perspective camera at eye looking at target (gluLookAt + gluPerspective conventions):
// what tests and asset generators use to draw synthetic strokes.
inline CameraMatrices look_at_camera(const Eigen::Vector3d& eye, const Eigen::Vector3d& target,
                                     const Eigen::Vector3d& up = Eigen::Vector3d::UnitY(), double fov_y = 0.8,
                                     double width = 800, double height = 600, double near_plane = 0.1,
                                     double far_plane = 50) {
  CameraMatrices c;
  const Eigen::Vector3d f = (target - eye).normalized(), s = f.cross(up).normalized(), u = s.cross(f);
  c.view.setIdentity();
  c.view.block<1, 3>(0, 0) = s.transpose();
  c.view.block<1, 3>(1, 0) = u.transpose();
  c.view.block<1, 3>(2, 0) = -f.transpose();
  c.view(0, 3) = -s.dot(eye);
  c.view(1, 3) = -u.dot(eye);
  c.view(2, 3) = f.dot(eye);
  const double t = 1 / std::tan(fov_y / 2);
  c.projection.setZero();
  c.projection(0, 0) = t * height / width;
  c.projection(1, 1) = t;
  c.projection(2, 2) = -(far_plane + near_plane) / (far_plane - near_plane);
  c.projection(2, 3) = -2 * far_plane * near_plane / (far_plane - near_plane);
  c.projection(3, 2) = -1;
  c.viewport = {0, 0, width, height};
  return c;
}

}  // namespace lapis::geometry
