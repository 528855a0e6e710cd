#include <doctest/doctest.h>

#include <functional>
#include <random>

#include "lapis/viewer/orbit_camera.h"
#include "lapis/viewer/renderer.h"

using namespace lapis;
using namespace lapis::viewer;

TEST_CASE("viewer: project then unproject returns the world point, and rays pass through it") {
  OrbitCamera cam;
  cam.frame(Eigen::Vector3d(-1, -2, -1), Eigen::Vector3d(1, 2, 1));
  cam.orbit(120, -40);
  const CameraMatrices m = cam.matrices(800, 600);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 100; ++k) {
    const Eigen::Vector3d p(u(rng), 2 * u(rng), u(rng));
    const Eigen::Vector3d s = geometry::project(m, p);
    CHECK((geometry::unproject(m, s.x(), s.y(), s.z()) - p).norm() < 1e-8);
    const geometry::Ray ray = geometry::unproject_ray(m, s.x(), s.y());
    const Eigen::Vector3d to_p = p - ray.origin;
    CHECK((to_p - to_p.dot(ray.direction) * ray.direction).norm() < 1e-8);
    CHECK(to_p.dot(ray.direction) > 0);
  }
  CHECK((geometry::eye_position(m) - cam.eye()).norm() < 1e-9);
}

TEST_CASE("viewer: framing puts the whole box on screen, from any orbit angle") {
  OrbitCamera cam;
  const Eigen::Vector3d lo(-3, 0, -1), hi(5, 2, 0.5);
  for (double yaw : {0.0, 1.0, 2.5, -2.0}) {
    cam.yaw = yaw;
    cam.frame(lo, hi);
    const CameraMatrices m = cam.matrices(640, 480);
    for (int c = 0; c < 8; ++c) {
      const Eigen::Vector3d corner((c & 1) ? hi.x() : lo.x(), (c & 2) ? hi.y() : lo.y(), (c & 4) ? hi.z() : lo.z());
      const Eigen::Vector3d s = geometry::project(m, corner);
      CHECK(s.x() >= 0);
      CHECK(s.x() <= 640);
      CHECK(s.y() >= 0);
      CHECK(s.y() <= 480);
      CHECK(s.z() > 0);
      CHECK(s.z() < 1);
    }
  }
}

TEST_CASE("viewer: orbit, pan and zoom move the camera as a user expects") {
  OrbitCamera cam;
  cam.frame(Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(1, 1, 1));
  const double d0 = cam.distance;
  cam.zoom(3);
  CHECK(cam.distance < d0);
  const Eigen::Vector3d t0 = cam.target;
  cam.pan(100, 0, 600);  // dragging right moves the scene right: the target moves left
  const Eigen::Vector3d right = cam.view().block<1, 3>(0, 0).transpose();
  CHECK((cam.target - t0).dot(right) < 0);
  const double pitch0 = cam.pitch;
  for (int k = 0; k < 1000; ++k) cam.orbit(0, 50);  // never flips over the pole
  CHECK(cam.pitch < 1.56);
  CHECK(cam.pitch > pitch0);
  CHECK(cam.view().allFinite());
}

namespace {

// A triangle "a" and a line strip "s".
Scene triangle_and_strip() {
  Scene scene;
  scene.meshes["a"].mesh.V.resize(3, 3);
  scene.meshes["a"].mesh.V << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  scene.meshes["a"].mesh.F.resize(1, 3);
  scene.meshes["a"].mesh.F << 0, 1, 2;
  scene.lines["s"].add_strip({Eigen::Vector3f(0, 0, 0), Eigen::Vector3f(0, 1, 0)});
  return scene;
}

}  // namespace

TEST_CASE("viewer: the counting renderer sees what a scene holds") {
  Scene scene = triangle_and_strip();
  scene.lines["s"].add_strip({Eigen::Vector3f(1, 0, 0), Eigen::Vector3f(1, 1, 0), Eigen::Vector3f(1, 2, 0)});
  CountingRenderer r;
  r.render(scene, {}, 10, 10);
  CHECK(r.triangles == 1);
  CHECK(r.strips == 2);
  scene.lines["s"].visible = false;
  r.render(scene, {}, 10, 10);
  CHECK(r.strips == 0);
  Eigen::Vector3d lo, hi;
  REQUIRE(scene.bounds(lo, hi));
  CHECK(hi.x() == 1.0);
}

TEST_CASE("viewer: the scene signature changes with whatever the picture shows, and only then") {
  Scene scene = triangle_and_strip();
  scene.points["p"].points.resize(1, 3);
  OrbitCamera cam;
  cam.frame(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones());
  const geometry::CameraMatrices m = cam.matrices(640, 480);
  const std::uint64_t base = scene_signature(scene, m, 640, 480);
  CHECK(scene_signature(scene, m, 640, 480) == base);  // nothing changed: the same picture

  // Each change a renderer would draw differently.
  const std::vector<std::function<void(Scene&)>> edits{
      [](Scene& s) { ++s.meshes["a"].version; },       [](Scene& s) { s.meshes["a"].visible = false; },
      [](Scene& s) { s.meshes["a"].alpha = 0.5f; },    [](Scene& s) { s.meshes["a"].base_color.x() = 0; },
      [](Scene& s) { ++s.lines["s"].version; },        [](Scene& s) { s.lines["s"].width = 3; },
      [](Scene& s) { s.lines["s"].on_top = true; },    [](Scene& s) { s.lines["s"].shading = LineShading::KajiyaKay; },
      [](Scene& s) { s.points["p"].size = 2; },        [](Scene& s) { ++s.points["p"].version; },
      [](Scene& s) { s.meshes["b"] = s.meshes["a"]; }, [](Scene& s) { s.lines.erase("s"); },
      [](Scene& s) { s.background.y() = 1; },
  };
  for (size_t k = 0; k < edits.size(); ++k) {
    CAPTURE(k);
    Scene changed = scene;
    edits[k](changed);
    CHECK(scene_signature(changed, m, 640, 480) != base);
  }
  OrbitCamera turned = cam;
  turned.orbit(3, 0);
  CHECK(scene_signature(scene, turned.matrices(640, 480), 640, 480) != base);
  CHECK(scene_signature(scene, cam.matrices(641, 480), 641, 480) != base);
}
