// The hairstyle as an undoable document: the head reference, grid, growth and
// sketch settings, the camera, the style primitives (thesis §4.5) and the strokes they were
// drawn with. Every change is a Command; the Document keeps undo and redo stacks of
// (command, inverse) pairs, so undo restores the previous state exactly.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <Eigen/Core>

#include "lapis/geometry/camera.h"
#include "lapis/hair_field/field_solver.h"
#include "lapis/hair_sketch/dividing_curve.h"
#include "lapis/hair_sketch/field_detail.h"
#include "lapis/hair_sketch/gravity_prior.h"
#include "lapis/hair_sketch/growth.h"
#include "lapis/hair_sketch/ponytail.h"
#include "lapis/hair_sketch/sketch.h"
#include "lapis/hair_sketch/strand_detail.h"
#include "lapis/hair_sketch/stream_curve.h"

namespace lapis::hair_sketch {

// One style primitive with the viewpoint its supporting surface is built from (§4.5: "the
// user can freely change the viewpoint of a stream curve and/or switch between the two
// supporting surface modes").
struct StylePrimitive {
  std::variant<StreamCurve, DividingCurve, Ponytail> shape;
  Eigen::Vector3d viewpoint = Eigen::Vector3d::Zero();
  SupportMode support = SupportMode::Strip;
  // Symmetric sketching (symmetry.h): the mirror image across the head's sagittal plane is part
  // of the style too, a twin that follows every edit of this primitive.
  bool mirrored = false;
};
// "stream_curve", "dividing_curve" or "ponytail".
const char* primitive_type(const StylePrimitive& p);
// Bitwise equality of every field (what undo and replay promise).
bool same_primitive(const StylePrimitive& a, const StylePrimitive& b);

struct HairstyleSettings {
  std::string head_mesh;         // path; relative paths are relative to the session file
  std::string scalp_mask;        // path or empty (cap above a plane, see load_head)
  hair_field::GridOptions grid;  // grid.target_unknowns: thesis §4.6
  hair_field::FieldMethod field_method = hair_field::FieldMethod::Auto;
  hair_field::FieldSolverOptions field;      // field.omega: constraint weight ω, thesis §4.4.1
  FieldDetailOptions field_detail;           // δᵢ of Eq. 4.1 from an example field (§4.7); off by default
  GravityPriorOptions gravity_prior;         // hair falls where nothing is sketched; off by default
  RootOptions roots;                         // roots.count strands to grow, roots.seed their jitter (§4.6)
  GrowthOptions growth;                      // growth.step l and growth.max_length, thesis §4.6;
                                             // growth.keep_outside_head and .head_clearance
  bool scalp_avoidance = true;               // thesis §4.6's one-shot avoidance step before growing
  SupportMode support = SupportMode::Strip;  // supporting surface of new curves
  SketchOptions sketch;                      // sketch.tail_segments of new stream curves (§4.5); its
                                             // spacing is the grid's (sketch_options)
};
// Equal in what a session stores: the paths, grid.target_unknowns, field_method,
// field.omega, field_detail, gravity_prior.strength, roots.count and .seed, growth.step, .max_length,
// .keep_outside_head and .head_clearance, scalp_avoidance, support and sketch.tail_segments.
bool operator==(const HairstyleSettings& a, const HairstyleSettings& b);

// What a recorded stroke did: create a primitive or edit primitive `target`.
enum class StrokeAction { StreamCurve, DividingCurve, Hint, Tilt, Ponytail };
const char* to_string(StrokeAction a);

struct RecordedStroke {
  StrokeAction action = StrokeAction::StreamCurve;
  int target = -1;                  // Hint, Tilt: the edited primitive's index
  geometry::CameraMatrices camera;  // as drawn
  std::vector<Stroke> strokes;      // one, or four for a ponytail
  // A ponytail whose strokes were drawn from different views: one camera per stroke. Empty:
  // every stroke was drawn with `camera`.
  std::vector<geometry::CameraMatrices> cameras;
  bool mirrored = false;  // created with symmetric sketching on
};
bool operator==(const RecordedStroke& a, const RecordedStroke& b);

struct Hairstyle {
  HairstyleSettings settings;
  geometry::CameraMatrices camera;
  std::vector<StylePrimitive> primitives;
  std::vector<RecordedStroke> strokes;  // the input that made `primitives`, in order
  std::vector<StrandDetail> details;    // applied to the grown strands in order (§4.7)
};
bool same_hairstyle(const Hairstyle& a, const Hairstyle& b);

// The changes a command can make.
struct InsertPrimitive {
  int index = 0;
  StylePrimitive primitive;
};
struct RemovePrimitive {
  int index = 0;
};
struct ReplacePrimitive {
  int index = 0;
  StylePrimitive primitive;
};
struct SetCamera {
  geometry::CameraMatrices camera;
};
struct SetSettings {
  HairstyleSettings settings;
};
// The whole detail stack: adding, editing, reordering or removing a detail is one command
// whose inverse is the stack before it.
struct SetDetails {
  std::vector<StrandDetail> details;
};
using Change = std::variant<InsertPrimitive, RemovePrimitive, ReplacePrimitive, SetCamera, SetSettings, SetDetails>;

struct Command {
  std::string name;  // for the Edit menu: "add stream curve", ...
  Change change;
  std::optional<RecordedStroke> stroke;  // appended to the stroke log, removed on undo
};

class Document {
 public:
  explicit Document(Hairstyle style = {});
  const Hairstyle& style() const { return style_; }

  // Applies the command, pushes it on the undo stack, clears redo. Throws InvalidArgument
  // for an index out of range; the document is then unchanged.
  void execute(Command command);
  bool can_undo() const { return !undo_.empty(); }
  bool can_redo() const { return !redo_.empty(); }
  // Throw InvalidArgument when there is nothing to undo / redo.
  void undo();
  void redo();
  const std::string& undo_name() const;  // empty when nothing to undo
  const std::string& redo_name() const;
  // Incremented by every execute, undo and redo: views re-solve when it changes.
  std::uint64_t revision() const { return revision_; }

 private:
  struct Entry {
    Command forward, backward;
  };
  Command apply(const Command& command);  // returns the inverse
  Hairstyle style_;
  std::vector<Entry> undo_, redo_;
  std::uint64_t revision_ = 0;
};

}  // namespace lapis::hair_sketch
