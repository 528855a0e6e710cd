// The hairstyle document: commands from strokes, undo/redo of every command restoring the
// document and the field, rejected strokes changing nothing.
#include <doctest/doctest.h>

#include "lapis/core/error.h"
#include "sketch_fixture.h"

using namespace hair_test;

namespace {

double max_difference(const Field& a, const Field& b) { return (a - b).cwiseAbs().maxCoeff(); }

// An empty document with the small test settings, and its grid.
struct Fresh {
  const Head& head = bundled_head();
  Document doc{Hairstyle{small_settings(), {}, {}, {}, {}}};
  Grid grid = hairstyle_grid(head, doc.style().settings);
};

}  // namespace

TEST_CASE("hair_sketch: undo of every command restores the document and the field; redo re-applies" *
          doctest::test_suite("slow")) {
  Fresh f;
  const Head& head = f.head;
  Document& doc = f.doc;
  const Grid& grid = f.grid;
  StyleField field(head, grid, FieldMethod::Thesis);
  field.update(doc.style().primitives);

  std::vector<Hairstyle> states{doc.style()};
  std::vector<Field> fields{field.field()};
  const auto record = [&] {
    field.update(doc.style().primitives);
    states.push_back(doc.style());
    fields.push_back(field.field());
  };
  const auto cam = right_camera(), top = top_camera();
  apply_stroke(doc, recorded(StrokeAction::StreamCurve, cam, {surface_stroke(cam, {0.4, 1, 0}, {0.2, 0, -1}, 1.2, 10)}),
               head, grid);
  CHECK(doc.undo_name() == "add stream curve");
  record();
  apply_stroke(
      doc, recorded(StrokeAction::StreamCurve, cam, {surface_stroke(cam, {0.7, 0.8, 0.2}, {0.3, -0.5, -1}, 1.0, 8)}),
      head, grid);
  record();
  apply_stroke(doc,
               recorded(StrokeAction::DividingCurve, top, {surface_stroke(top, {-0.1, 1, 0.5}, {0, 0.1, -1}, 0.7)}),
               head, grid);
  record();
  // Tilt: a stroke from the parting's start outward on one side.
  {
    const auto& dc = std::get<DividingCurve>(doc.style().primitives[2].shape);
    const Eigen::Vector3d foot = dc.points[1], x0 = dividing_side_axis(dc, head, 0.1);
    std::vector<Eigen::Vector3d> pts;
    for (int k = 1; k <= 6; ++k)
      pts.push_back(on_head(foot + 0.05 * k * x0 + 0.02 * k * Eigen::Vector3d(0, 0, 1) - head.center));
    apply_stroke(doc, recorded(StrokeAction::Tilt, top, {project_path(top, pts)}, 2), head, grid);
    CHECK(doc.undo_name() == "tilt parting");
    CHECK(std::get<DividingCurve>(doc.style().primitives[2].shape).alpha0 != 0.0);
    record();
  }
  // Cut curve 0 with a stroke across its middle (strip seen from its own viewpoint).
  {
    const auto& c0 = std::get<StreamCurve>(doc.style().primitives[0].shape).points;
    const Eigen::Vector2d mid = lapis::geometry::project(cam, c0[c0.size() / 2]).head<2>();
    const Eigen::Vector2d next = lapis::geometry::project(cam, c0[c0.size() / 2 + 1]).head<2>();
    const Eigen::Vector2d across = Eigen::Vector2d(-(next - mid).y(), (next - mid).x()).normalized();
    Stroke cut;
    for (int k = -12; k <= 12; ++k) cut.push_back(mid + 8.0 * k * across);  // from beyond "near"
    apply_stroke(doc, recorded(StrokeAction::Hint, cam, {cut}, 0), head, grid);
    CHECK(doc.undo_name() == "cut curve");
    record();
  }
  doc.execute({"remove stream curve", RemovePrimitive{1}, std::nullopt});
  record();
  doc.execute({"move camera", SetCamera{top}, std::nullopt});
  record();
  HairstyleSettings changed = doc.style().settings;
  changed.roots.count = 123;
  doc.execute({"settings", SetSettings{changed}, std::nullopt});
  record();
  CHECK(doc.style().strokes.size() == 5);

  const double scale = std::max(1.0, fields.back().cwiseAbs().maxCoeff());
  const auto matches = [&](size_t i) {
    CAPTURE(i);
    field.update(doc.style().primitives);
    CHECK(same_hairstyle(doc.style(), states[i]));
    CHECK(max_difference(field.field(), fields[i]) <= 1e-9 * scale);
  };
  for (int i = static_cast<int>(states.size()) - 2; i >= 0; --i) {
    REQUIRE(doc.can_undo());
    doc.undo();
    matches(static_cast<size_t>(i));
  }
  CHECK_FALSE(doc.can_undo());
  CHECK_THROWS_WITH_AS(doc.undo(), "hair_sketch::Document::undo(): nothing to undo", lapis::InvalidArgument);
  for (size_t i = 1; i < states.size(); ++i) {
    REQUIRE(doc.can_redo());
    doc.redo();
    matches(i);
  }
  CHECK_FALSE(doc.can_redo());
  // A new command after an undo drops the redo branch.
  doc.undo();
  doc.execute({"remove", RemovePrimitive{0}, std::nullopt});
  CHECK_FALSE(doc.can_redo());
}

TEST_CASE("hair_sketch: a rejected stroke or command leaves the document unchanged") {
  Fresh f;
  const Head& head = f.head;
  Document& doc = f.doc;
  const Grid& grid = f.grid;
  const auto cam = right_camera();
  apply_stroke(doc, recorded(StrokeAction::StreamCurve, cam, {surface_stroke(cam, {0.4, 1, 0}, {0.2, 0, -1}, 1.2)}),
               head, grid);
  const Hairstyle before = doc.style();
  const auto rev = doc.revision();
  const auto rejected = [&](const RecordedStroke& r, const char* reason) {
    CHECK_THROWS_WITH_AS(apply_stroke(doc, r, head, grid), doctest::Contains(reason), StrokeRejected);
    CHECK(same_hairstyle(doc.style(), before));
    CHECK(doc.revision() == rev);
  };
  rejected(recorded(StrokeAction::StreamCurve, cam, {{{3, 3}, {40, 50}}}), "stroke misses the head");
  rejected(recorded(StrokeAction::StreamCurve, cam, {{{400, 300}}}), "expected at least 2");
  rejected(recorded(StrokeAction::StreamCurve, cam, {{{400, 300}, {400.5, 300}, {400, 300.5}}}), "degenerate stroke");
  rejected(recorded(StrokeAction::Hint, cam, {{{3, 3}, {40, 50}}}, 7), "target 7 is not a primitive index");
  rejected(recorded(StrokeAction::Tilt, cam, {{{3, 3}, {40, 50}}}, 0), "is a stream_curve, expected a dividing curve");
  rejected(recorded(StrokeAction::Ponytail, cam, {{{3, 3}, {40, 50}}}), "needs 4 stroke(s), got 1");
  rejected(recorded(StrokeAction::Hint, cam, {{{3, 3}, {40, 50}}}, 0),
           "does not start on the curve's supporting surface");
  CHECK_THROWS_WITH_AS(doc.execute({"bad", RemovePrimitive{3}, std::nullopt}),
                       doctest::Contains("remove index 3 out of range"), lapis::InvalidArgument);
  CHECK(same_hairstyle(doc.style(), before));
}
