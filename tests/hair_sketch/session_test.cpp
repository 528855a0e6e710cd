// Sessions: JSON round trip, replay of recorded strokes to identical strands, atomic saves
// under SIGKILL, hostile files, and the bundled example sessions against their reports.
#include <doctest/doctest.h>

#include <sys/wait.h>
#include <unistd.h>
#include <csignal>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "lapis/core/error.h"
#include "lapis/hair_sketch/export.h"
#include "lapis/hair_sketch/hair_file.h"
#include "lapis/hair_sketch/session.h"
#include "sketch_fixture.h"

using namespace hair_test;
namespace fs = std::filesystem;

namespace {

fs::path temp_path(const std::string& name) { return hair_test::temp_path("lapis_hair_session_test", name); }

// A small session drawn with strokes: two stream curves, a parting, a tilt and a hint.
Hairstyle drawn_session() {
  const Head& head = bundled_head();
  Hairstyle start;
  start.settings = small_settings();
  start.settings.head_mesh = "head.obj";
  Document doc(start);
  const Grid grid = hairstyle_grid(head, start.settings);
  const auto cam = right_camera(), top = top_camera();
  apply_stroke(doc, recorded(StrokeAction::StreamCurve, cam, {surface_stroke(cam, {0.4, 1, 0}, {0.2, 0, -1}, 1.2, 10)}),
               head, grid);
  apply_stroke(
      doc, recorded(StrokeAction::StreamCurve, cam, {surface_stroke(cam, {0.7, 0.8, 0.2}, {0.3, -0.5, -1}, 1.0, 8)}),
      head, grid);
  apply_stroke(doc,
               recorded(StrokeAction::DividingCurve, top, {surface_stroke(top, {-0.1, 1, 0.5}, {0, 0.1, -1}, 0.7)}),
               head, grid);
  // Concatenate onto curve 1: from its end, further down in the picture.
  const auto& c1 = std::get<StreamCurve>(doc.style().primitives[1].shape).points;
  Stroke more = curve_on_screen(cam, c1, 0.9, 0.9);
  for (int k = 1; k <= 10; ++k) more.push_back(more.front() + Eigen::Vector2d(-2.0 * k, 6.0 * k));
  apply_stroke(doc, recorded(StrokeAction::Hint, cam, {more}, 1), head, grid);
  return doc.style();
}

std::string text_of(const fs::path& p) {
  std::ifstream in(p);
  return {std::istreambuf_iterator<char>(in), {}};
}

}  // namespace

TEST_CASE("hair_sketch: session save, load and replay give identical documents and strands") {
  const Head& head = bundled_head();
  const Hairstyle drawn = drawn_session();
  REQUIRE(drawn.strokes.size() == 4);
  const fs::path p = temp_path("drawn.json");
  save_session(p, drawn);
  const Hairstyle loaded = load_session(p);
  CHECK(same_hairstyle(loaded, drawn));  // bit-identical numbers through JSON
  const Hairstyle replayed = replay_strokes(loaded, head);
  CHECK(same_hairstyle(replayed, drawn));
  const HairstyleResult a = build_hairstyle(drawn, head), b = build_hairstyle(replayed, head);
  REQUIRE(a.strands.count() > 0.9 * drawn.settings.roots.count);  // roots sample θ, φ steps: about `roots`
  CHECK(a.strands.offsets == b.strands.offsets);
  CHECK(a.strands.points == b.strands.points);
  CHECK(a.penetrating_segments == b.penetrating_segments);
  CHECK(a.strands.segments() > a.strands.count());  // the field grew hair
  // The thesis' growth, without the head check, is a setting a session keeps.
  Hairstyle thesis = drawn;
  thesis.settings.growth.keep_outside_head = false;
  thesis.settings.growth.head_clearance = 0.1;
  save_session(p, thesis);
  const Hairstyle thesis_loaded = load_session(p);
  CHECK_FALSE(thesis_loaded.settings.growth.keep_outside_head);
  CHECK(thesis_loaded.settings.growth.head_clearance == 0.1);
  CHECK(same_hairstyle(thesis_loaded, thesis));
  CHECK_FALSE(thesis_loaded.settings == drawn.settings);
}

TEST_CASE("hair_sketch: a session saved while the process is killed is never truncated") {
  Hairstyle big = drawn_session();
  for (int i = 0; i < 6; ++i) big.primitives.insert(big.primitives.end(), big.primitives.begin(), big.primitives.end());
  const fs::path p = temp_path("killed.json");
  save_session(p, big);
  const auto size = fs::file_size(p);
  for (int round = 0; round < 6; ++round) {
    const pid_t child = fork();
    REQUIRE(child >= 0);
    if (child == 0) {
      for (;;) save_session(p, big);  // until killed
    }
    usleep(3000 + 4000 * round);
    kill(child, SIGKILL);
    int status = 0;
    waitpid(child, &status, 0);
    CHECK(WIFSIGNALED(status));
    CHECK(fs::file_size(p) == size);
    CHECK(same_hairstyle(load_session(p), big));
  }
}

TEST_CASE("hair_sketch: malformed and hostile sessions give clear errors") {
  const std::string good = session_to_json(drawn_session());
  const auto mutate = [&](const std::function<void(nlohmann::json&)>& f) {
    nlohmann::json j = nlohmann::json::parse(good);
    f(j);
    return j.dump();
  };
  const auto fails = [](const std::string& text, const std::string& what) {
    CHECK_THROWS_WITH_AS(session_from_json(text, "s.json"), doctest::Contains(what.c_str()), lapis::IoError);
  };
  CHECK_NOTHROW(session_from_json(good));
  fails("{\"format\": ", "s.json: $: malformed JSON");
  fails("[1, 2]", "$: expected an object, got array");
  fails(mutate([](auto& j) { j["format"] = "other"; }), "$.format: expected \"lapis-hair-session\"");
  fails(mutate([](auto& j) { j["settings"]["grid_unknowns"] = "many"; }),
        "$.settings.grid_unknowns: expected a number, got string");
  fails(mutate([](auto& j) { j["settings"].erase("roots"); }), "$.settings: missing key \"roots\"");
  fails(mutate([](auto& j) { j["settings"]["roots"] = -5; }), "$.settings.roots: expected an integer in [0, ");
  fails(mutate([](auto& j) { j["settings"]["step"] = 0; }),
        "$.settings.step: expected a finite number in [0.001, 10], found 0");
  // An unsigned integer beyond long long is refused, not wrapped to -1 (a valid target).
  fails(mutate([](auto& j) { j["strokes"][0]["target"] = 18446744073709551615ull; }),
        "$.strokes[0].target: expected an integer in [-1, 1073741824], found 18446744073709551615");
  fails(mutate([](auto& j) { j["primitives"][0]["points"][2][1] = nullptr; }),  // NaN is written as null
        "$.primitives[0].points[2][1]: expected a number, got null");
  fails(mutate([](auto& j) { j["primitives"][1]["type"] = "braid"; }), "$.primitives[1].type: expected stream_curve");
  fails(mutate([](auto& j) { j["camera"]["view"].erase(3); }), "$.camera.view: expected 16 elements, got 15");
  fails(mutate([](auto& j) { j["strokes"][0]["action"] = 3; }), "$.strokes[0].action: expected a string, got number");
  fails(mutate([](auto& j) {
          j["strokes"][0]["strokes"][0] = nlohmann::json::array({1, 2});
        }),
        "$.strokes[0].strokes[0][0]: expected an array, got number");
  std::string inf = good;
  const auto from = inf.find("\"omega\": ") + 9;
  inf.replace(from, inf.find_first_of(",\n}", from) - from, "1e999");
  fails(inf, "$: malformed JSON: [json.exception.out_of_range.406] number overflow");  // not an infinite omega
  // A huge array is refused by its length, before any of it is converted.
  nlohmann::json huge = nlohmann::json::parse(good);
  huge["primitives"][0]["points"] = nlohmann::json::array();
  for (int i = 0; i < 100001; ++i) huge["primitives"][0]["points"].push_back(nlohmann::json::array({0, 0, 0}));
  fails(huge.dump(), "$.primitives[0].points: 100001 elements, at most 100000 allowed");
  SessionLimits tiny;
  tiny.max_file_bytes = 100;
  const fs::path p = temp_path("big.json");
  std::ofstream(p) << good;
  CHECK_THROWS_WITH_AS(load_session(p, tiny), doctest::Contains("at most 100 allowed"), lapis::IoError);
  CHECK_THROWS_WITH_AS(load_session(temp_path("absent.json")), doctest::Contains("cannot read"), lapis::IoError);
}

// Strands whose polyline crosses the disc of radius 1.2 r around the ponytail's first
// cross-section C1 (thesis §4.5): the hair the tail gathers.
static int strands_through_first_section(const Strands& strands, const Ponytail& tail) {
  const Ponytail::Section c1 = tail.first_section();
  int through = 0;
  for (int s = 0; s < strands.count(); ++s) {
    for (int i = strands.offsets[s]; i + 1 < strands.offsets[s + 1]; ++i) {
      const Eigen::Vector3d a = strands.points[i].cast<double>() - c1.center;
      const Eigen::Vector3d b = strands.points[i + 1].cast<double>() - c1.center;
      const double ha = a.dot(c1.normal), hb = b.dot(c1.normal);
      if ((ha < 0) == (hb < 0)) continue;
      const Eigen::Vector3d x = a + (ha / (ha - hb)) * (b - a);
      if (x.norm() <= 1.2 * c1.radius) {
        ++through;
        break;
      }
    }
  }
  return through;
}

TEST_CASE("hair_sketch: each bundled example session replays to the counts of its report" *
          doctest::test_suite("slow")) {
  const fs::path dir = fs::path(LAPIS_SOURCE_DIR) / "assets" / "sessions";
  int found = 0;
  for (const char* name : {"smooth", "parting", "ponytails", "curly_bob", "wavy_long", "half_up"}) {
    CAPTURE(name);
    const fs::path session = dir / (std::string(name) + ".json");
    REQUIRE(fs::exists(session));
    const Hairstyle stored = load_session(session);
    const Head head = load_session_head(stored, session);
    const Hairstyle style = replay_strokes(stored, head);
    CHECK(same_hairstyle(style, stored));  // the primitives are what the strokes make
    const HairstyleResult r = build_hairstyle(style, head);
    const auto report = nlohmann::json::parse(text_of(dir / (std::string(name) + ".report.json")));
    const Strands grown = grown_strands(r.strands);  // what lapis hair exports and reports
    CHECK(grown.count() == report["strands"].get<int>());
    CHECK(grown.segments() == report["segments"].get<int>());
    CHECK(r.strands.count() - grown.count() == report["roots_without_hair"].get<int>());
    CHECK(r.penetrating_segments == report["penetrating_segments"].get<int>());
    // Growth keeps the strands out of the head (GrowthOptions::keep_outside_head): at most a
    // segment in 10,000 may dip in (none does today), where the avoidance alone left 0.4–4%.
    CHECK(r.penetrating_segments <= grown.segments() / 10000);
    // Each of the two ponytails gathers a fifth of the hair or more; the half-up tail gathers
    // the hair above the dividing curves, a smaller share.
    const int share = std::string(name) == "half_up" ? 20 : 5;
    for (const auto& p : style.primitives)
      if (const auto* tail = std::get_if<Ponytail>(&p.shape)) {
        CHECK(strands_through_first_section(r.strands, *tail) >= r.strands.count() / share);
        const auto [entered, through] = strands_entering_tail(r.strands, *tail, r.grid.spacing);
        MESSAGE(std::string(name) << ": " << through << " of " << entered
                                  << " strands entering a tail pass through C1");
        CHECK(through >= 0.9 * entered);
      }
    // The export is a .hair file that reads back under strict validation, strand for strand.
    const fs::path hair = temp_path(std::string(name) + ".hair");
    write_hair_file(hair, to_hair_file(grown));
    const Strands back = strands_from_hair_file(read_hair_file(hair));
    CHECK(back.offsets == grown.offsets);
    CHECK(back.points == grown.points);
    ++found;
  }
  CHECK(found == 6);
}

TEST_CASE("hair_sketch: the curly bob with the app's 20K strands keeps its curls out of the head" *
          doctest::test_suite("slow")) {
  // Curls wound close to the scalp cut through it between clear points where it curves
  // tightly; detail's last pass takes the segments out (258 of 2.29M stayed in without it).
  const fs::path session = fs::path(LAPIS_SOURCE_DIR) / "assets" / "sessions" / "curly_bob.json";
  Hairstyle style = load_session(session);
  const Head head = load_session_head(style, session);
  style.settings.roots.count = 20000;
  const HairstyleResult r = build_hairstyle(style, head);
  MESSAGE(r.penetrating_segments << " of " << r.strands.segments() << " segments in the head");
  CHECK(r.strands.segments() > 2'000'000);
  CHECK(r.penetrating_segments <= r.strands.segments() / 100000);
}

TEST_CASE("hair_sketch: a saved session names its head relative to itself, and finds it again") {
  const fs::path assets = fs::weakly_canonical(fs::path(LAPIS_SOURCE_DIR) / "assets");
  Hairstyle style;
  style.settings.head_mesh = (assets / "head.obj").string();
  style.settings.scalp_mask = (assets / "head_scalp.txt").string();
  const fs::path p = temp_path("sub/relative.json");
  fs::create_directories(p.parent_path());
  save_session(p, style);
  const Hairstyle loaded = load_session(p);
  CHECK(fs::path(loaded.settings.head_mesh).is_relative());
  CHECK(fs::path(loaded.settings.scalp_mask).is_relative());
  const Head head = load_session_head(loaded, p);
  CHECK(head.scalp_face_count() > 0);
  // Relative paths are stored as they are: relative to the session already.
  style.settings.head_mesh = "../head.obj";
  save_session(p, style);
  CHECK(load_session(p).settings.head_mesh == "../head.obj");
}
