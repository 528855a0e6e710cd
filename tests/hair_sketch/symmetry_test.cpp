// Symmetric sketching: a primitive's twin across the sagittal plane has the mirror image of its
// constraints, a mirrored stroke makes a mirrored primitive, and undo removes both.
#include <doctest/doctest.h>

#include <filesystem>

#include "lapis/hair_sketch/session.h"
#include "lapis/hair_sketch/symmetry.h"
#include "sketch_fixture.h"

using namespace hair_test;

namespace {

const std::filesystem::path kSessions = std::filesystem::path(LAPIS_SOURCE_DIR) / "assets" / "sessions";

// Largest difference between two constraint lists as sets (merged: sorted by node).
double set_difference(const std::vector<Constraint>& a, const std::vector<Constraint>& b) {
  const ConstraintSet x = ConstraintSet::from(a), y = ConstraintSet::from(b);
  if (x.size() != y.size()) {
    MESSAGE("constraint counts differ: " << x.size() << " and " << y.size());
    return 1e300;
  }
  double worst = 0;
  for (int i = 0; i < x.size(); ++i) {
    if (x.items()[i].node != y.items()[i].node) return 1e300;
    worst = std::max(worst, (x.items()[i].direction - y.items()[i].direction).cwiseAbs().maxCoeff());
  }
  return worst;
}

}  // namespace

TEST_CASE("hair_sketch: a twin's constraints are the mirror image of its primitive's") {
  const Head& head = bundled_head();
  for (const char* name : {"smooth", "parting", "ponytails"}) {
    const Hairstyle style = load_session(kSessions / (std::string(name) + ".json"));
    const Grid grid = hairstyle_grid(head, style.settings);
    // The grid is symmetric about the sagittal plane, so mirrored nodes are nodes.
    CHECK(std::abs(grid.origin.x() + grid.max_corner().x() - 2 * head.center.x()) < 1e-12);
    for (StylePrimitive p : style.primitives) {
      const std::string what = std::string(name) + " " + primitive_type(p);
      CAPTURE(what);
      if (auto* d = std::get_if<DividingCurve>(&p.shape)) d->alpha0 = 0.4, d->alpha1 = -0.2;  // tilted both ways
      const auto own = primitive_constraints(p, grid, head);
      const auto twin = primitive_constraints(mirror_image(p, head.center.x()), grid, head);
      REQUIRE(!own.empty());
      CHECK(set_difference(twin, mirror_constraints(own, grid)) < 1e-12);
      // Marked mirrored, the primitive brings both.
      p.mirrored = true;
      std::vector<Constraint> both = own;
      both.insert(both.end(), twin.begin(), twin.end());
      CHECK(set_difference(primitive_constraints(p, grid, head), both) == 0);
    }
  }
}

TEST_CASE("hair_sketch: a mirrored stroke makes a mirrored primitive; undo removes it and its twin") {
  const Head& head = bundled_head();
  Hairstyle start;
  start.settings = small_settings();
  Document doc(start);
  const Grid grid = hairstyle_grid(head, start.settings);
  const auto cam = right_camera();
  RecordedStroke stroke =
      recorded(StrokeAction::StreamCurve, cam, {surface_stroke(cam, {0.4, 1, 0}, {0.2, 0, -1}, 1.2, 10)});
  stroke.mirrored = true;
  apply_stroke(doc, stroke, head, grid);
  REQUIRE(doc.style().primitives.size() == 1);
  CHECK(doc.style().primitives[0].mirrored);
  const ConstraintSet set = style_constraints(doc.style().primitives, grid, head);
  StylePrimitive alone = doc.style().primitives[0];
  alone.mirrored = false;
  CHECK(set.size() > ConstraintSet::from(primitive_constraints(alone, grid, head)).size());
  // The session keeps the flag on the primitive and on the stroke; replay makes the same.
  const Hairstyle reloaded = session_from_json(session_to_json(doc.style()));
  CHECK(same_hairstyle(reloaded, doc.style()));
  CHECK(same_hairstyle(replay_strokes(reloaded, head), doc.style()));
  doc.undo();
  CHECK(doc.style().primitives.empty());
  CHECK(style_constraints(doc.style().primitives, grid, head).empty());
}
