// Strand detail as part of a hairstyle: undoable document entries, saved in sessions, and
// reapplied by the interactive loop without a solve or a regrowth when only they change.
#include <doctest/doctest.h>

#include <cmath>

#include "lapis/core/error.h"
#include "lapis/hair_sketch/live_hairstyle.h"
#include "lapis/hair_sketch/session.h"
#include "sketch_fixture.h"

using namespace hair_test;

namespace {

// One stream curve down the back of the head, with the small test settings.
Hairstyle back_style() {
  Hairstyle h;
  h.settings = small_settings();
  h.settings.head_mesh = "head.obj";
  StreamCurve c;
  for (int i = 0; i <= 20; ++i) {
    const double a = 0.25 + 1.6 * i / 20.0;
    c.points.emplace_back(0.35, 1.25 * std::cos(a), -1.25 * std::sin(a));
  }
  h.primitives.push_back({c});
  return h;
}

std::vector<StrandDetail> some_details() {
  StrandDetail curl, clump, cut;
  curl.shape = CurlDetail{};
  curl.region = {1, 2, 3};
  clump.shape = ClumpDetail{};
  clump.seed = 9;
  CutDetail line;
  line.camera = right_camera();
  line.line = {Eigen::Vector2d(0, 500), Eigen::Vector2d(800, 520)};
  cut.shape = line;
  return {clump, curl, cut};
}

}  // namespace

TEST_CASE("hair_sketch: details are undoable document entries and round-trip through sessions") {
  Document doc(back_style());
  const Hairstyle before = doc.style();
  doc.execute({"add details", SetDetails{some_details()}, std::nullopt});
  CHECK(doc.style().details.size() == 3);
  CHECK_FALSE(same_hairstyle(doc.style(), before));
  const Hairstyle with = doc.style();
  doc.undo();
  CHECK(same_hairstyle(doc.style(), before));
  doc.redo();
  CHECK(same_hairstyle(doc.style(), with));

  const auto path = temp_path("lapis_detail_document_test", "details.json");
  save_session(path, with);
  CHECK(same_hairstyle(load_session(path), with));  // bit-identical parameters, cameras and regions
  Hairstyle field_waves = with;                     // and the field detail settings
  field_waves.settings.field_detail.amplitude = 0.3;
  field_waves.settings.field_detail.wavelength = 0.7;
  CHECK(same_hairstyle(session_from_json(session_to_json(field_waves)), field_waves));
  CHECK_FALSE(same_hairstyle(field_waves, with));
  CHECK(replay_strokes(with, bundled_head()).details.size() == 3);  // details are not strokes: kept

  StrandDetail bad;
  CurlDetail negative;
  negative.radius = -1;
  bad.shape = negative;
  CHECK_THROWS_AS(doc.execute({"bad", SetDetails{{bad}}, std::nullopt}), lapis::InvalidArgument);
  CHECK(same_hairstyle(doc.style(), with));
  std::string text = session_to_json(with);
  text.replace(text.find("\"clump\""), 7, "\"curly\"");
  CHECK_THROWS_WITH_AS(session_from_json(text), doctest::Contains("$.details[0].type"), lapis::IoError);
}

TEST_CASE("hair_sketch: a detail edit reapplies detail to the grown strands, the same as a fresh build") {
  const Head& head = bundled_head();
  Hairstyle style = back_style();
  LiveHairstyle live(head, style.settings);
  const LiveUpdate plain = live.update(style.primitives);
  CHECK(plain.regrown);
  style.details = some_details();
  const LiveUpdate detailed = live.update(style.primitives, style.details);
  CHECK_FALSE(detailed.regrown);
  CHECK(detailed.solves.empty());
  const HairstyleResult fresh = build_hairstyle(style, head);
  CHECK(detailed.strands.offsets == fresh.strands.offsets);
  CHECK(detailed.strands.points == fresh.strands.points);
  CHECK(detailed.strands.points != plain.strands.points);
  const LiveUpdate undone = live.update(style.primitives, std::vector<StrandDetail>{});
  CHECK_FALSE(undone.regrown);
  CHECK(undone.strands.points == plain.strands.points);

  StrandDetail outside;
  outside.shape = FrizzDetail{};
  outside.region = {head.mesh.num_vertices()};
  CHECK_THROWS_WITH_AS(live.update(style.primitives, {outside}), doctest::Contains("region vertex"),
                       lapis::InvalidArgument);
}

TEST_CASE("hair_sketch: after several edits, a live hairstyle's field is a fresh build's (avoidance found once)") {
  // LiveHairstyle keeps the scalp avoidance's near-head nodes from its first update; a later
  // edit must still give the field build_hairstyle gives from scratch (up to the incremental
  // solve's rounding).
  const Head& head = bundled_head();
  Hairstyle style = back_style();
  style.settings.gravity_prior.strength = 0.3;
  LiveHairstyle live(head, style.settings);
  live.update(style.primitives);
  StreamCurve side;
  for (int i = 0; i <= 16; ++i) {
    const double a = 0.3 + 1.2 * i / 16.0;
    side.points.emplace_back(1.2 * std::sin(a), 1.2 * std::cos(a), 0.2);
  }
  style.primitives.push_back({side});
  const LiveUpdate edited = live.update(style.primitives);
  REQUIRE(edited.solves.size() == 2);  // the style, then the avoidance
  // The avoidance solve has a solver of its own, so it too sees only the edit's diff, not the
  // near-head nodes leaving and coming back.
  const auto changed_nodes = [](const lapis::hair_field::FieldSolveReport& r) { return r.added + r.removed; };
  MESSAGE("nodes added or removed: style " << changed_nodes(edited.solves[0]) << ", avoidance "
                                           << changed_nodes(edited.solves[1]));
  CHECK(changed_nodes(edited.solves[0]) > 0);
  CHECK(changed_nodes(edited.solves[1]) <= changed_nodes(edited.solves[0]) + 10);
  const HairstyleResult fresh = build_hairstyle(style, head);
  const double scale = fresh.field.cwiseAbs().maxCoeff();
  const double difference = (live.field() - fresh.field).cwiseAbs().maxCoeff();
  MESSAGE("largest field difference " << difference << " of " << scale);
  CHECK(difference <= 1e-6 * scale);
  CHECK(edited.strands.offsets == fresh.strands.offsets);
}

TEST_CASE("hair_sketch: a live preview grows every k-th strand as the update does, point for point") {
  // An app that draws every k-th strand shows the preview's strands first; the update then
  // grows the rest in the same field and must give those strands unchanged, details included.
  const Head& head = bundled_head();
  const Hairstyle style = back_style();
  StrandDetail curl, frizz, length, clump;
  curl.shape = CurlDetail{};  // a phase and a radius drawn per strand: the strand's own index decides
  frizz.shape = FrizzDetail{};
  frizz.seed = 4;
  length.shape = LengthDetail{};
  length.region = {1, 2, 3, 40, 41, 42};
  clump.shape = ClumpDetail{.clumps = 12};  // guides among all the strands, grown with the preview
  clump.seed = 3;
  const std::vector<StrandDetail> details = {curl, clump, frizz, length};
  const int stride = 7;
  LiveHairstyle live(head, style.settings);
  const LiveUpdate preview = live.preview(style.primitives, details, stride);
  CHECK(preview.solves.size() == 2);
  const LiveUpdate full = live.update(style.primitives, details);
  CHECK(full.solves.empty());  // the preview's solve holds
  CHECK(full.regrown);
  REQUIRE(preview.strands.count() == (full.strands.count() + stride - 1) / stride);
  const auto strand = [](const Strands& s, int i) {
    return std::vector<Eigen::Vector3f>(s.points.begin() + s.offsets[i], s.points.begin() + s.offsets[i + 1]);
  };
  const auto differing = [&](const Strands& subset, const Strands& whole) {
    int n = 0;
    for (int k = 0; k < subset.count(); ++k) n += strand(subset, k) != strand(whole, k * stride);
    return n;
  };
  CHECK(differing(preview.strands, full.strands) == 0);
  CHECK(full.strands.points.size() > 4 * preview.strands.points.size());
  // The clump moved strands: without it, the preview differs.
  const LiveUpdate unclumped = live.preview(style.primitives, {curl, frizz, length}, stride);
  CHECK(differing(unclumped.strands, full.strands) > preview.strands.count() / 4);

  // The update after a preview is a fresh update; a preview after an update takes its strands.
  LiveHairstyle fresh(head, style.settings);
  CHECK(fresh.update(style.primitives, details).strands.points == full.strands.points);
  const LiveUpdate plain = live.update(style.primitives, std::vector<StrandDetail>{});
  const LiveUpdate again = live.preview(style.primitives, std::vector<StrandDetail>{}, stride);
  CHECK(again.solves.empty());
  REQUIRE(again.strands.count() == preview.strands.count());
  CHECK(differing(again.strands, plain.strands) == 0);
  CHECK_THROWS_AS(live.preview(style.primitives, {}, 0), lapis::InvalidArgument);
}
