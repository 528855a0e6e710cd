// Strokes to document commands.
#include "lapis/hair_sketch/stroke_commands.h"

#include "lapis/hair_sketch/style_field.h"

namespace lapis::hair_sketch {
using hair_field::Grid;

namespace {

constexpr const char* kFn = "hair_sketch::command_from_stroke()";

[[noreturn]] void reject(const std::string& reason) { throw StrokeRejected(std::string(kFn) + ": " + reason); }

template <class T>
const T& target_shape(const Hairstyle& style, const RecordedStroke& s, const char* kind) {
  if (s.target < 0 || s.target >= static_cast<int>(style.primitives.size()))
    reject(std::string(to_string(s.action)) + " target " + std::to_string(s.target) +
           " is not a primitive index (there are " + std::to_string(style.primitives.size()) + ")");
  const auto* shape = std::get_if<T>(&style.primitives[s.target].shape);
  if (!shape)
    reject(std::string(to_string(s.action)) + " target " + std::to_string(s.target) + " is a " +
           primitive_type(style.primitives[s.target]) + ", expected a " + kind);
  return *shape;
}

}  // namespace

Command command_from_stroke(const Hairstyle& style, const RecordedStroke& s, const Head& head, const Grid& grid) {
  const size_t expected = s.action == StrokeAction::Ponytail ? 4 : 1;
  if (s.strokes.size() != expected)
    reject(std::string(to_string(s.action)) + " needs " + std::to_string(expected) + " stroke(s), got " +
           std::to_string(s.strokes.size()));
  const SketchOptions opt = sketch_options(grid, style.settings);
  const Eigen::Vector3d eye = geometry::eye_position(s.camera);
  const int end = static_cast<int>(style.primitives.size());
  Command c;
  c.stroke = s;
  switch (s.action) {
    case StrokeAction::StreamCurve:
      c.name = "add stream curve";
      c.change = InsertPrimitive{
          end, {stream_curve_from_stroke(s.strokes[0], s.camera, head, opt), eye, style.settings.support}};
      break;
    case StrokeAction::DividingCurve:
      c.name = "add dividing curve";
      c.change = InsertPrimitive{
          end, {dividing_curve_from_stroke(s.strokes[0], s.camera, head, opt), eye, style.settings.support}};
      break;
    case StrokeAction::Ponytail: {
      c.name = "add ponytail";
      const std::array<Stroke, 4> four{s.strokes[0], s.strokes[1], s.strokes[2], s.strokes[3]};
      if (!s.cameras.empty() && s.cameras.size() != 4) reject("a ponytail needs 4 cameras or none");
      const std::array<geometry::CameraMatrices, 4> cameras =
          s.cameras.empty() ? std::array{s.camera, s.camera, s.camera, s.camera}
                            : std::array{s.cameras[0], s.cameras[1], s.cameras[2], s.cameras[3]};
      // The viewpoint is the spine's (its supporting surface is seen from there).
      c.change = InsertPrimitive{
          end,
          {ponytail_from_strokes(four, cameras, head, opt), geometry::eye_position(cameras[0]), SupportMode::Strip}};
      break;
    }
    case StrokeAction::Hint: {
      // Stream curves and ponytail spines are edited alike (§4.5: "the creation and
      // editing of the spine curve is the same as that of a stream curve").
      if (s.target < 0 || s.target >= end) target_shape<StreamCurve>(style, s, "stream curve");
      StylePrimitive p = style.primitives[s.target];
      std::vector<Eigen::Vector3d>* curve = nullptr;
      if (auto* sc = std::get_if<StreamCurve>(&p.shape))
        curve = &sc->points;
      else if (auto* pt = std::get_if<Ponytail>(&p.shape))
        curve = &pt->spine;
      else
        target_shape<StreamCurve>(style, s, "stream curve or ponytail");
      const HintEdit edit = interpret_hint(*curve, p.viewpoint, p.support, s.strokes[0], s.camera, opt);
      *curve = edit.points;
      c.name = std::string(to_string(edit.kind)) + " curve";
      c.change = ReplacePrimitive{s.target, std::move(p)};
      break;
    }
    case StrokeAction::Tilt: {
      const auto& curve = target_shape<DividingCurve>(style, s, "dividing curve");
      StylePrimitive p = style.primitives[s.target];
      p.shape = interpret_tilt(curve, s.strokes[0], s.camera, head, opt).curve;
      c.name = "tilt parting";
      c.change = ReplacePrimitive{s.target, std::move(p)};
      break;
    }
  }
  if (auto* insert = std::get_if<InsertPrimitive>(&c.change)) insert->primitive.mirrored = s.mirrored;
  return c;
}

void apply_stroke(Document& document, const RecordedStroke& stroke, const Head& head, const Grid& grid) {
  document.execute(command_from_stroke(document.style(), stroke, head, grid));
}

Hairstyle replay_strokes(const Hairstyle& session, const Head& head) {
  Hairstyle start;
  start.settings = session.settings;
  start.camera = session.camera;
  start.details = session.details;  // not made by strokes: carried as they are
  Document doc(std::move(start));
  const Grid grid = hairstyle_grid(head, session.settings);
  for (size_t i = 0; i < session.strokes.size(); ++i) {
    try {
      apply_stroke(doc, session.strokes[i], head, grid);
    } catch (const StrokeRejected& e) {
      throw StrokeRejected("hair_sketch::replay_strokes(): stroke " + std::to_string(i) + ": " + e.what());
    }
  }
  return doc.style();
}

}  // namespace lapis::hair_sketch
