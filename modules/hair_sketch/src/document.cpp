// The undoable hairstyle document: commands and their inverses.
#include "lapis/hair_sketch/document.h"

#include <limits>

#include "lapis/core/error.h"

namespace lapis::hair_sketch {
namespace {

bool same_points(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b) { return a == b; }

bool same_shape(const StreamCurve& a, const StreamCurve& b) {
  return same_points(a.points, b.points) && a.tail_segments == b.tail_segments;
}
bool same_shape(const DividingCurve& a, const DividingCurve& b) {
  return same_points(a.points, b.points) && a.alpha0 == b.alpha0 && a.alpha1 == b.alpha1 && a.sigma == b.sigma &&
         a.height == b.height && a.discontinuity == b.discontinuity && a.samples_per_side == b.samples_per_side;
}
bool same_shape(const Ponytail& a, const Ponytail& b) {
  return same_points(a.spine, b.spine) && same_points(a.cross_section, b.cross_section) &&
         same_points(a.profile_a, b.profile_a) && same_points(a.profile_b, b.profile_b) && a.tightness == b.tightness &&
         a.inner_ratio == b.inner_ratio && a.outer_ratio == b.outer_ratio;
}

bool same_camera(const geometry::CameraMatrices& a, const geometry::CameraMatrices& b) {
  return a.view == b.view && a.projection == b.projection && a.viewport == b.viewport;
}

void check_index(int index, int size, const char* what) {
  if (index < 0 || index >= size)
    throw InvalidArgument(std::string("hair_sketch::Document::execute(): ") + what + " index " + std::to_string(index) +
                          " out of range [0, " + std::to_string(size) + ")");
}

}  // namespace

const char* primitive_type(const StylePrimitive& p) {
  static const char* names[] = {"stream_curve", "dividing_curve", "ponytail"};
  return names[p.shape.index()];
}

bool same_primitive(const StylePrimitive& a, const StylePrimitive& b) {
  if (a.shape.index() != b.shape.index() || a.viewpoint != b.viewpoint || a.support != b.support ||
      a.mirrored != b.mirrored)
    return false;
  return std::visit([&](const auto& x) { return same_shape(x, std::get<std::decay_t<decltype(x)>>(b.shape)); },
                    a.shape);
}

bool operator==(const HairstyleSettings& a, const HairstyleSettings& b) {
  return a.head_mesh == b.head_mesh && a.scalp_mask == b.scalp_mask &&
         a.grid.target_unknowns == b.grid.target_unknowns && a.field_method == b.field_method &&
         a.field.omega == b.field.omega && a.field_detail.amplitude == b.field_detail.amplitude &&
         a.field_detail.wavelength == b.field_detail.wavelength &&
         a.gravity_prior.strength == b.gravity_prior.strength && a.roots.count == b.roots.count &&
         a.roots.seed == b.roots.seed && a.growth.step == b.growth.step && a.growth.max_length == b.growth.max_length &&
         a.growth.keep_outside_head == b.growth.keep_outside_head &&
         a.growth.head_clearance == b.growth.head_clearance && a.scalp_avoidance == b.scalp_avoidance &&
         a.support == b.support && a.sketch.tail_segments == b.sketch.tail_segments;
}

const char* to_string(StrokeAction a) {
  static const char* names[] = {"stream_curve", "dividing_curve", "hint", "tilt", "ponytail"};
  return names[static_cast<int>(a)];
}

bool operator==(const RecordedStroke& a, const RecordedStroke& b) {
  if (a.cameras.size() != b.cameras.size()) return false;
  for (std::size_t i = 0; i < a.cameras.size(); ++i)
    if (!same_camera(a.cameras[i], b.cameras[i])) return false;
  return a.action == b.action && a.target == b.target && same_camera(a.camera, b.camera) && a.strokes == b.strokes &&
         a.mirrored == b.mirrored;
}

bool same_hairstyle(const Hairstyle& a, const Hairstyle& b) {
  if (!(a.settings == b.settings) || !same_camera(a.camera, b.camera) || a.strokes != b.strokes ||
      a.primitives.size() != b.primitives.size() || a.details.size() != b.details.size())
    return false;
  for (size_t i = 0; i < a.details.size(); ++i)
    if (!same_detail(a.details[i], b.details[i])) return false;
  for (size_t i = 0; i < a.primitives.size(); ++i)
    if (!same_primitive(a.primitives[i], b.primitives[i])) return false;
  return true;
}

Document::Document(Hairstyle style) : style_(std::move(style)) {}

Command Document::apply(const Command& c) {
  auto& prims = style_.primitives;
  const int n = static_cast<int>(prims.size());
  Command inverse{c.name, SetCamera{style_.camera}, std::nullopt};
  std::visit(
      [&](const auto& ch) {
        using T = std::decay_t<decltype(ch)>;
        if constexpr (std::is_same_v<T, InsertPrimitive>) {
          if (ch.index < 0 || ch.index > n) check_index(ch.index, n + 1, "insert");
          prims.insert(prims.begin() + ch.index, ch.primitive);
          inverse.change = RemovePrimitive{ch.index};
        } else if constexpr (std::is_same_v<T, RemovePrimitive>) {
          check_index(ch.index, n, "remove");
          inverse.change = InsertPrimitive{ch.index, prims[ch.index]};
          prims.erase(prims.begin() + ch.index);
        } else if constexpr (std::is_same_v<T, ReplacePrimitive>) {
          check_index(ch.index, n, "replace");
          inverse.change = ReplacePrimitive{ch.index, prims[ch.index]};
          prims[ch.index] = ch.primitive;
        } else if constexpr (std::is_same_v<T, SetCamera>) {
          inverse.change = SetCamera{style_.camera};
          style_.camera = ch.camera;
        } else if constexpr (std::is_same_v<T, SetDetails>) {
          for (const auto& d : ch.details) check_detail(d, std::numeric_limits<int>::max(), "hair_sketch::Document");
          inverse.change = SetDetails{style_.details};
          style_.details = ch.details;
        } else {
          inverse.change = SetSettings{style_.settings};
          style_.settings = ch.settings;
        }
      },
      c.change);
  ++revision_;
  return inverse;
}

void Document::execute(Command command) {
  Command inverse = apply(command);  // throws before changing anything
  if (command.stroke) style_.strokes.push_back(*command.stroke);
  undo_.push_back({std::move(command), std::move(inverse)});
  redo_.clear();
}

void Document::undo() {
  if (undo_.empty()) throw InvalidArgument("hair_sketch::Document::undo(): nothing to undo");
  Entry e = std::move(undo_.back());
  undo_.pop_back();
  apply(e.backward);
  if (e.forward.stroke) style_.strokes.pop_back();
  redo_.push_back(std::move(e));
}

void Document::redo() {
  if (redo_.empty()) throw InvalidArgument("hair_sketch::Document::redo(): nothing to redo");
  Entry e = std::move(redo_.back());
  redo_.pop_back();
  apply(e.forward);
  if (e.forward.stroke) style_.strokes.push_back(*e.forward.stroke);
  undo_.push_back(std::move(e));
}

const std::string& Document::undo_name() const {
  static const std::string none;
  return undo_.empty() ? none : undo_.back().forward.name;
}

const std::string& Document::redo_name() const {
  static const std::string none;
  return redo_.empty() ? none : redo_.back().forward.name;
}

}  // namespace lapis::hair_sketch
