// Sketch interpretation (thesis §4.5, Fig. 4.3): what a 2D mouse stroke means in 3D. A
// stroke arrives as screen points (pixels, y down) plus the camera it was drawn with, so
// every function here is pure and testable headless. Depth comes from the scalp (stream and
// dividing curves) or from a curve's supporting surface (hint strokes, ponytail curves).
// A stroke that cannot be interpreted throws StrokeRejected with the reason; callers
// apply nothing then, which is how a rejected stroke leaves the document unchanged.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "lapis/core/error.h"
#include "lapis/geometry/camera.h"
#include "lapis/hair_sketch/dividing_curve.h"
#include "lapis/hair_sketch/head.h"
#include "lapis/hair_sketch/ponytail.h"
#include "lapis/hair_sketch/stream_curve.h"

namespace lapis::hair_sketch {

// Screen points in pixels (y down), in drawing order.
using Stroke = std::vector<Eigen::Vector2d>;

// A stroke that cannot be interpreted; what() is "<function>: <reason>".
class StrokeRejected : public InvalidArgument {
 public:
  using InvalidArgument::InvalidArgument;
};

struct SketchOptions {
  double spacing = 0.1;          // grid spacing d: style curves are resampled at d (§4.5)
  double lift = 0.1;             // curve points stay this far (in d) above the scalp
  double surface_width = 6;      // supporting surface half-width, in d ("its neighborhood")
  double near = 1.5;             // a hint point within this many d of the curve is "near" it
  double min_stroke_pixels = 4;  // a shorter stroke (screen arc length) is degenerate
  int tail_segments = 3;         // fading tail of created stream curves (§4.5, Fig. 4.5 left)
};

// Fig. 4.3(a) and (b): the ruled surface through the curve and its viewpoint, or the strip
// of lines orthogonal to each segment–viewpoint triangle. The ruled surface is degenerate
// seen from its own viewpoint: the user edits on it after turning the camera.
enum class SupportMode { Ruled, Strip };
const char* to_string(SupportMode m);

// The surface as rulings: points[i] + w * rulings[i], |w| <= half_width.
struct SupportingSurface {
  std::vector<Eigen::Vector3d> points;   // the curve
  std::vector<Eigen::Vector3d> rulings;  // unit, one per point
  double half_width = 0;

  struct Hit {
    Eigen::Vector3d point;
    double s = 0;     // arc length along the curve of the hit's foot
    double w = 0;     // signed offset along the ruling
    double t = 0;     // ray parameter
    bool on = false;  // |w| <= half_width
  };
  // The hit of the ray with the surface (or its extension beyond half_width, flagged
  // on = false), or nothing when the ray passes the curve's ends or runs along the surface.
  std::optional<Hit> intersect(const geometry::Ray& ray) const;
  double length() const;
};

// Throws InvalidArgument for fewer than 2 points or the viewpoint on the curve's line.
SupportingSurface make_supporting_surface(const std::vector<Eigen::Vector3d>& curve, const Eigen::Vector3d& viewpoint,
                                          SupportMode mode, const SketchOptions& options);

// §4.5: starts on the scalp (depth of the hit); later points take the depth of their scalp
// hit while on the scalp, else the depth of the last scalp point; points are then kept at
// least `lift` above the head and resampled at d. Rejects a stroke with fewer than 2 points,
// non-finite or too short, or one that does not start on the scalp.
StreamCurve stream_curve_from_stroke(const Stroke& stroke, const geometry::CameraMatrices& camera, const Head& head,
                                     const SketchOptions& options);

// §4.5: a dividing curve is drawn on the scalp; every point must hit it.
DividingCurve dividing_curve_from_stroke(const Stroke& stroke, const geometry::CameraMatrices& camera, const Head& head,
                                         const SketchOptions& options);

// Fig. 4.3(c)–(h): a hint stroke starting on the curve's supporting surface is
//   Insert       starts and ends near the curve: the stroke replaces the part between,
//   Concatenate  starts near, ends far (or off the surface, depth extrapolated from the
//                last on-surface segment): the curve ends at the start and continues along
//                the stroke,
//   Cut          starts away from the curve and runs across it: the curve ends there.
enum class HintKind { Cut, Concatenate, Insert };
const char* to_string(HintKind k);

struct HintEdit {
  HintKind kind = HintKind::Cut;
  std::vector<Eigen::Vector3d> points;  // the edited curve, resampled at d
};

// Rejects strokes that are degenerate, do not start on the surface, or match no rule.
HintEdit interpret_hint(const std::vector<Eigen::Vector3d>& curve, const Eigen::Vector3d& viewpoint, SupportMode mode,
                        const Stroke& stroke, const geometry::CameraMatrices& camera, const SketchOptions& options);

// §4.5, Fig. 4.4: a hint stroke on the scalp beside a dividing curve, drawn away from the
// parting, gives the hair's flow direction on its side: α is the angle about the scalp
// normal from the untilted side axis to the stroke. It sets α0 when the stroke is nearer
// the curve's start, α1 when nearer its end. `side` reports +1 / -1 (dividing_side_axis).
struct TiltEdit {
  DividingCurve curve;
  int end = 0;  // 0: α0 changed, 1: α1 changed
  int side = 1;
};
TiltEdit interpret_tilt(const DividingCurve& curve, const Stroke& stroke, const geometry::CameraMatrices& camera,
                        const Head& head, const SketchOptions& options);

// §4.5, Fig. 4.5 right: the spine is created like a stream curve; the cross section and the
// two profiles are drawn on the spine's supporting surface (strip mode, seen from the
// spine's viewpoint = this camera's eye). strokes = {spine, cross section, profile a,
// profile b}.
Ponytail ponytail_from_strokes(const std::array<Stroke, 4>& strokes, const geometry::CameraMatrices& camera,
                               const Head& head, const SketchOptions& options);
// The same with each stroke's own camera: the spine's surface is built from cameras[0]'s eye
// and each other stroke is read with its camera's rays, so the user can turn the view between
// the spine and the other strokes (§4.5).
Ponytail ponytail_from_strokes(const std::array<Stroke, 4>& strokes,
                               const std::array<geometry::CameraMatrices, 4>& cameras, const Head& head,
                               const SketchOptions& options);

}  // namespace lapis::hair_sketch
