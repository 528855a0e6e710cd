// A 3D transform gizmo for the apps: three world axes with arrows (translate along an axis),
// three rings (rotate about an axis) and a square at the centre (scale uniformly). It keeps
// a constant size on screen, is drawn as scene lines, is hit-tested against the mouse in
// pixels, and turns a mouse drag into a similarity transform about its centre. Pure math on
// the camera matrices: no GL, no window, so every mapping is unit-tested.
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "lapis/geometry/camera.h"
#include "lapis/viewer/scene.h"

namespace lapis::viewer {

enum class GizmoPart { None, TranslateX, TranslateY, TranslateZ, RotateX, RotateY, RotateZ, Scale };

const char* to_string(GizmoPart p);
// The world axis (0, 1, 2) a translate or rotate part acts along / about; -1 for Scale/None.
int gizmo_axis(GizmoPart p);

struct GizmoOptions {
  double size_px = 110;           // arrow length on screen; the gizmo keeps it at any zoom
  double ring_fraction = 0.72;    // ring radius as a fraction of the arrow length
  double shaft_start = 0.25;      // arrows are grabbable from here (fraction of the length), so
                                  // the centre square stays free for scaling
  double square_fraction = 0.14;  // half side of the scale square, fraction of the length
  double pick_tolerance_px = 8;   // how close the cursor must come to a part to grab it
  int ring_segments = 64;
};

class Gizmo {
 public:
  explicit Gizmo(GizmoOptions options = {});

  // Where the gizmo is drawn (the active handle's centroid where its transform puts it). Also
  // mid-drag, so the gizmo follows the handle; the drag's mapping stays anchored at the centre
  // the drag started from.
  void set_center(const Eigen::Vector3d& center);
  const Eigen::Vector3d& center() const { return center_; }
  const GizmoOptions& options() const { return options_; }

  // World length of the arrows at the centre's depth for this camera (size_px on screen).
  double world_size(const geometry::CameraMatrices& camera) const;

  // The part under the pixel (within pick_tolerance_px), the nearest one if several.
  GizmoPart hit(const geometry::CameraMatrices& camera, const Eigen::Vector2d& pixel) const;

  // Grabs the part under the pixel; false (and nothing changes) when there is none.
  bool begin_drag(const geometry::CameraMatrices& camera, const Eigen::Vector2d& pixel);
  // The transform from the drag's start to the cursor now: world 4x4, a translation along
  // the grabbed axis, a rotation about it through the centre, or a uniform scale about the
  // centre of exp(travel / size_px), travel the cursor's screen distance outwards from where
  // it grabbed the square (size_px out doubles it 2.7 times, as far in shrinks it as much).
  // Uses the camera and the centre of begin_drag(). Identity when no drag is running.
  Eigen::Matrix4d drag_to(const Eigen::Vector2d& pixel);
  void end_drag();
  bool dragging() const { return active_ != GizmoPart::None; }
  GizmoPart active() const { return active_; }

  // Highlighted part (hover feedback); the dragged part is always highlighted.
  GizmoPart hovered = GizmoPart::None;

  // Fills `item` with the gizmo's lines (per-point colours, drawn on top of the meshes).
  void draw(const geometry::CameraMatrices& camera, LineItem& item) const;

 private:
  struct Polyline {
    GizmoPart part;
    std::vector<Eigen::Vector3d> points;
    bool closed;
  };
  std::vector<Polyline> parts(const geometry::CameraMatrices& camera) const;
  double world_size_at(const geometry::CameraMatrices& camera, const Eigen::Vector3d& point) const;

  GizmoOptions options_;
  Eigen::Vector3d center_ = Eigen::Vector3d::Zero();
  // Drag state.
  Eigen::Vector3d anchor_ = Eigen::Vector3d::Zero();  // the centre when the drag began
  GizmoPart active_ = GizmoPart::None;
  geometry::CameraMatrices drag_camera_;
  Eigen::Vector2d start_pixel_ = Eigen::Vector2d::Zero();
  double start_parameter_ = 0;          // translate: position along the axis under the start pixel
  double last_angle_ = 0, turned_ = 0;  // rotate: screen angle last seen, total (unwrapped)
};

// Building blocks, public for tests.

// Parameter t of the point center + t * axis closest to the ray (axis unit length); nullopt
// when the ray runs (nearly) parallel to the axis.
std::optional<double> closest_axis_parameter(const geometry::Ray& ray, const Eigen::Vector3d& center,
                                             const Eigen::Vector3d& axis);

// Distance in pixels from p to the segment ab.
double distance_to_segment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b);

// The 4x4 of a rotation by `angle` about the world line through `center` along unit `axis`,
// of a uniform scale about `center`, and of a translation.
Eigen::Matrix4d rotation_about(const Eigen::Vector3d& center, const Eigen::Vector3d& axis, double angle);
Eigen::Matrix4d scale_about(const Eigen::Vector3d& center, double factor);
Eigen::Matrix4d translation(const Eigen::Vector3d& offset);

}  // namespace lapis::viewer
