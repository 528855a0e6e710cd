// Uses the installed lapis::viewer (its GL-free part): an orbit camera framing a box sees the
// box in front of it. Exits 0 only when it does.
#include <cstdio>

#include "lapis/geometry/camera.h"
#include "lapis/viewer/orbit_camera.h"

int main() {
  lapis::viewer::OrbitCamera camera;
  const Eigen::Vector3d lo(-1, -1, -1), hi(1, 1, 1);
  camera.frame(lo, hi);
  const lapis::geometry::CameraMatrices m = camera.matrices(640, 480);
  const Eigen::Vector3d centre = lapis::geometry::project(m, Eigen::Vector3d::Zero());
  const bool outside = (camera.eye().array() > hi.array()).any() || (camera.eye().array() < lo.array()).any();
  const bool centred = std::abs(centre.x() - 320) < 1 && std::abs(centre.y() - 240) < 1;
  std::printf("viewer consumer: eye (%.2f, %.2f, %.2f), box centre at pixel (%.1f, %.1f): %s\n", camera.eye().x(),
              camera.eye().y(), camera.eye().z(), centre.x(), centre.y(), outside && centred ? "ok" : "FAILED");
  return outside && centred ? 0 : 1;
}
