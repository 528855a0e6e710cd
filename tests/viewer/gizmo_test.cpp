#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "lapis/viewer/gizmo.h"

using namespace lapis;
using namespace lapis::viewer;

namespace {

// Looking down -z at the origin from z = 5 (x right, y up on screen).
geometry::CameraMatrices front_camera() {
  return geometry::look_at_camera({0, 0, 5}, {0, 0, 0}, Eigen::Vector3d::UnitY(), 0.8, 800, 600);
}

// An oblique view, so no axis is edge-on or end-on.
geometry::CameraMatrices oblique_camera() {
  return geometry::look_at_camera({3, 2.5, 4}, {0.2, 0.1, -0.3}, Eigen::Vector3d::UnitY(), 0.8, 800, 600);
}

// A gizmo off the origin seen obliquely.
struct ObliqueSetup {
  Eigen::Vector3d center{0.2, 0.1, -0.3};
  geometry::CameraMatrices camera = oblique_camera();
  Gizmo gizmo;
  ObliqueSetup() { gizmo.set_center(center); }
};

Eigen::Vector2d pixel_of(const geometry::CameraMatrices& cam, const Eigen::Vector3d& p) {
  return geometry::project(cam, p).head<2>();
}

}  // namespace

TEST_CASE("viewer: gizmo keeps its size on screen at any distance") {
  Gizmo g;
  for (double dist : {2.0, 5.0, 20.0}) {
    const auto cam = geometry::look_at_camera({0, 0, dist}, {0, 0, 0}, Eigen::Vector3d::UnitY(), 0.8, 800, 600);
    const double L = g.world_size(cam);
    const Eigen::Vector2d c = pixel_of(cam, g.center()), tip = pixel_of(cam, g.center() + L * Eigen::Vector3d::UnitX());
    CHECK((tip - c).norm() == doctest::Approx(g.options().size_px).epsilon(1e-6));
  }
}

TEST_CASE("viewer: gizmo hit test finds each axis arrow, each ring and the centre square") {
  const ObliqueSetup o;
  Gizmo g = o.gizmo;
  const Eigen::Vector3d center = o.center;
  const auto cam = o.camera;
  const double L = g.world_size(cam);
  const GizmoPart translate[3] = {GizmoPart::TranslateX, GizmoPart::TranslateY, GizmoPart::TranslateZ};
  const GizmoPart rotate[3] = {GizmoPart::RotateX, GizmoPart::RotateY, GizmoPart::RotateZ};
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3d axis = Eigen::Vector3d::Unit(a);
    CAPTURE(a);
    CHECK(g.hit(cam, pixel_of(cam, center + 0.85 * L * axis)) == translate[a]);
    // A point on ring a, off the other rings' planes.
    const Eigen::Vector3d u = Eigen::Vector3d::Unit((a + 1) % 3), v = Eigen::Vector3d::Unit((a + 2) % 3);
    const Eigen::Vector3d on_ring = center + g.options().ring_fraction * L * (std::cos(0.8) * u + std::sin(0.8) * v);
    CHECK(g.hit(cam, pixel_of(cam, on_ring)) == rotate[a]);
  }
  CHECK(g.hit(cam, pixel_of(cam, center)) == GizmoPart::Scale);
  // Far from everything: nothing.
  CHECK(g.hit(cam, pixel_of(cam, center) + Eigen::Vector2d(300, 250)) == GizmoPart::None);
}

TEST_CASE("viewer: dragging an arrow translates along its axis by what the cursor covered on that axis") {
  const ObliqueSetup o;
  Gizmo g = o.gizmo;
  const Eigen::Vector3d center = o.center;
  const auto cam = o.camera;
  const double L = g.world_size(cam);
  for (int a = 0; a < 3; ++a) {
    CAPTURE(a);
    const Eigen::Vector3d axis = Eigen::Vector3d::Unit(a);
    REQUIRE(g.begin_drag(cam, pixel_of(cam, center + 0.8 * L * axis)));
    CHECK(gizmo_axis(g.active()) == a);
    // Move the cursor onto the point 0.37 further along the axis: the transform moves the
    // centre by exactly that, along the axis only.
    const Eigen::Matrix4d T = g.drag_to(pixel_of(cam, center + (0.8 * L + 0.37) * axis));
    CHECK((T.topLeftCorner<3, 3>() - Eigen::Matrix3d::Identity()).norm() < 1e-12);
    CHECK((T.topRightCorner<3, 1>() - 0.37 * axis).norm() < 1e-9);
    // Back at the start pixel: no motion.
    CHECK((g.drag_to(pixel_of(cam, center + 0.8 * L * axis)) - Eigen::Matrix4d::Identity()).norm() < 1e-9);
    g.end_drag();
    CHECK(!g.dragging());
  }
}

TEST_CASE("viewer: a quarter turn of the cursor around a facing ring rotates a quarter turn about its axis") {
  Gizmo g;
  const auto cam = front_camera();  // +z points at the viewer
  const double r = g.options().ring_fraction * g.world_size(cam);
  const Eigen::Vector2d c = pixel_of(cam, g.center());
  REQUIRE(g.begin_drag(cam, pixel_of(cam, Eigen::Vector3d(r * std::cos(0.3), r * std::sin(0.3), 0))));
  REQUIRE(g.active() == GizmoPart::RotateZ);
  // Sweep counter-clockwise on screen in steps to 0.3 + pi/2 and then on past half a turn.
  Eigen::Matrix4d T;
  for (int k = 1; k <= 10; ++k) {
    const double t = 0.3 + k * (std::numbers::pi / 2) / 10;
    T = g.drag_to(c + 90 * Eigen::Vector2d(std::cos(t), -std::sin(t)));
  }
  const Eigen::Matrix3d expected = Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  CHECK((T.topLeftCorner<3, 3>() - expected).norm() < 1e-9);
  CHECK(T.topRightCorner<3, 1>().norm() < 1e-12);  // about the centre (the origin)
  for (int k = 11; k <= 30; ++k) {
    const double t = 0.3 + k * (std::numbers::pi / 2) / 10;
    T = g.drag_to(c + 90 * Eigen::Vector2d(std::cos(t), -std::sin(t)));
  }
  // Three quarter turns swept in total: the unwrapped angle, not -90°.
  const Eigen::AngleAxisd aa(Eigen::Matrix3d(T.topLeftCorner<3, 3>()));
  CHECK(std::abs(aa.angle() - std::numbers::pi / 2) < 1e-9);
  CHECK(aa.axis().z() == doctest::Approx(-1));  // 270° about +z is 90° about -z
}

TEST_CASE("viewer: rotation about a point and scale about a point keep that point fixed") {
  const Eigen::Vector3d c(1, -2, 0.5);
  const Eigen::Matrix4d R = rotation_about(c, Eigen::Vector3d(1, 1, 0), 0.7), S = scale_about(c, 2.5);
  CHECK(((R * c.homogeneous()).head<3>() - c).norm() < 1e-12);
  CHECK(((S * c.homogeneous()).head<3>() - c).norm() < 1e-12);
  CHECK(((S * Eigen::Vector4d(2, -2, 0.5, 1)).head<3>() - Eigen::Vector3d(3.5, -2, 0.5)).norm() < 1e-12);
}

TEST_CASE("viewer: the centre square scales in proportion to the pointer's travel, wherever it was grabbed") {
  Gizmo g;
  const Eigen::Vector3d center(0.5, 0, 0);
  g.set_center(center);
  const auto cam = front_camera();
  const Eigen::Vector2d c = pixel_of(cam, center);
  const double size = g.options().size_px;
  auto factor = [](const Eigen::Matrix4d& T) { return T.topLeftCorner<3, 3>().determinant(); };
  // Grabbed beside the centre: size_px · ln 2 outwards doubles, as far inwards halves.
  REQUIRE(g.begin_drag(cam, c + Eigen::Vector2d(6, 0)));
  REQUIRE(g.active() == GizmoPart::Scale);
  Eigen::Matrix4d T = g.drag_to(c + Eigen::Vector2d(6 + size * std::log(2.0), 0));
  CHECK((T.topLeftCorner<3, 3>() - 2 * Eigen::Matrix3d::Identity()).norm() < 1e-12);
  CHECK(((T * center.homogeneous()).head<3>() - center).norm() < 1e-12);
  T = g.drag_to(c + Eigen::Vector2d(6 - size * std::log(2.0), 0));
  CHECK(std::cbrt(factor(T)) == doctest::Approx(0.5));
  g.end_drag();
  // Grabbed at the very centre, a small move makes a small change, not a jump (it was 50×).
  REQUIRE(g.begin_drag(cam, c));
  T = g.drag_to(c + Eigen::Vector2d(10, -10));
  CHECK(std::cbrt(factor(T)) == doctest::Approx(std::exp(std::sqrt(200.0) / size)));
  CHECK(std::cbrt(factor(g.drag_to(c + Eigen::Vector2d(-3, 3)))) > 0.95);
  g.end_drag();
}

TEST_CASE("viewer: mid-drag the gizmo is drawn where its handle is, while the drag stays anchored") {
  Gizmo g;
  const Eigen::Vector3d center(0.5, 0, 0);
  g.set_center(center);
  const auto cam = front_camera();
  const double L = g.world_size(cam);
  const Eigen::Vector2d grab = pixel_of(cam, center + 0.8 * L * Eigen::Vector3d::UnitX());
  REQUIRE(g.begin_drag(cam, grab));
  REQUIRE(g.active() == GizmoPart::TranslateX);
  const Eigen::Vector2d to = grab + Eigen::Vector2d(80, 0);
  const Eigen::Matrix4d T = g.drag_to(to);
  REQUIRE(T(0, 3) > 0);
  // The app moves the gizmo with the handle every frame; the same pointer maps the same.
  g.set_center(center + T.topRightCorner<3, 1>());
  CHECK(g.center().x() == doctest::Approx(center.x() + T(0, 3)));
  CHECK((g.drag_to(to) - T).norm() == 0);
  viewer::LineItem item;
  g.draw(cam, item);
  Eigen::Vector3f mean = item.points.colwise().mean().transpose();
  CHECK(std::abs(mean.x() - static_cast<float>(g.center().x())) < 0.2 * L);  // drawn around the moved centre
  g.end_drag();
}

TEST_CASE("viewer: closest axis parameter and segment distance") {
  const geometry::Ray ray{{0, 0, 5}, {0, 0, -1}};
  const auto t = closest_axis_parameter(ray, Eigen::Vector3d(-2, 0, 0), Eigen::Vector3d::UnitX());
  REQUIRE(t);
  CHECK(*t == doctest::Approx(2));
  CHECK(!closest_axis_parameter(ray, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ()));
  CHECK(distance_to_segment({0, 1}, {-1, 0}, {1, 0}) == doctest::Approx(1));
  CHECK(distance_to_segment({3, 4}, {-1, 0}, {0, 0}) == doctest::Approx(5));
}

TEST_CASE("viewer: the gizmo draws seven parts on top, the dragged one highlighted") {
  Gizmo g;
  const auto cam = oblique_camera();
  LineItem item;
  g.draw(cam, item);
  CHECK(item.on_top);
  CHECK(item.num_strips() == 3 * 3 + 1);  // shaft, arrowhead, ring per axis; the square
  CHECK(item.colors.rows() == item.points.rows());
  const Eigen::Vector3f before = item.colors.row(0);
  REQUIRE(g.begin_drag(cam, pixel_of(cam, g.center() + 0.8 * g.world_size(cam) * Eigen::Vector3d::UnitX())));
  g.draw(cam, item);
  CHECK((Eigen::Vector3f(item.colors.row(0)) - before).norm() > 0.1);
}
