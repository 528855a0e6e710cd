#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>

#include "lapis/viewer/input_events.h"
#include "lapis/viewer/png.h"

using namespace lapis;
using namespace lapis::viewer;
namespace fs = std::filesystem;

namespace {

fs::path temp_file(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "lapis_viewer_test";
  fs::create_directories(dir);
  return dir / name;
}

void write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

}  // namespace

TEST_CASE("viewer: an event log round-trips through its file") {
  EventLog log;
  log.width = 800, log.height = 600;
  InputEvent a{EventType::MouseButton};
  a.frame = 3, a.time = 0.25, a.x = 10.5, a.y = 20, a.button = 0, a.action = 1, a.mods = 2;
  InputEvent b{EventType::Key};
  b.frame = 9, b.key = 83, b.action = 1, b.mods = 2;
  InputEvent c{EventType::Scroll};
  c.frame = 9, c.y = -1;
  log.events = {a, b, c};
  const fs::path p = temp_file("events.json");
  log.save(p);
  const EventLog back = EventLog::load(p);
  REQUIRE(back.events.size() == 3);
  CHECK(back.width == 800);
  CHECK(back.events[0].type == EventType::MouseButton);
  CHECK(back.events[0].x == 10.5);
  CHECK(back.events[0].mods == 2);
  CHECK(back.events[1].key == 83);
  CHECK(back.events[2].y == -1);
}

TEST_CASE("viewer: malformed event logs give an IoError naming the problem") {
  const fs::path p = temp_file("bad.json");
  write(p, "{not json");
  CHECK_THROWS_AS(EventLog::load(p), IoError);
  write(p, R"({"format":"something-else","width":1,"height":1,"events":[]})");
  CHECK_THROWS_WITH_AS(EventLog::load(p),
                       ("viewer::EventLog::load(): " + p.string() + ": 'format' is not \"lapis-events\"").c_str(),
                       IoError);
  write(p, R"({"format":"lapis-events","width":1,"height":1,"events":[{"type":"teleport","frame":0}]})");
  CHECK_THROWS_WITH_AS(EventLog::load(p),
                       ("viewer::EventLog::load(): " + p.string() + ": event 0: unknown event type 'teleport'").c_str(),
                       IoError);
  write(
      p,
      R"({"format":"lapis-events","width":1,"height":1,"events":[{"type":"move","frame":5},{"type":"move","frame":2}]})");
  CHECK_THROWS_WITH_AS(EventLog::load(p),
                       ("viewer::EventLog::load(): " + p.string() + ": event 1: frame 2 goes backwards").c_str(),
                       IoError);
  write(p, R"({"format":"lapis-events","width":1,"height":1,"events":[{"type":"move","frame":"x"}]})");
  CHECK_THROWS_AS(EventLog::load(p), IoError);
  // Integers are not truncated or wrapped: a key of 4294967297 is not key 1.
  write(p, R"({"format":"lapis-events","width":1,"height":1,"events":[{"type":"key","frame":0,"key":4294967297}]})");
  CHECK_THROWS_WITH_AS(
      EventLog::load(p),
      doctest::Contains("event 0: key: expected an integer in [-2147483648, 2147483647], found 4294967297"), IoError);
  write(p, R"({"format":"lapis-events","width":1,"height":1,"events":[{"type":"button","frame":1.5}]})");
  CHECK_THROWS_WITH_AS(EventLog::load(p), doctest::Contains("event 0: frame: expected an integer in [0, "), IoError);
  write(p, R"({"format":"lapis-events","width":4294967297,"height":1,"events":[]})");
  CHECK_THROWS_WITH_AS(EventLog::load(p),
                       doctest::Contains(": width: expected an integer in [0, 65536], found 4294967297"), IoError);
  CHECK_THROWS_AS(EventLog::load(temp_file("missing.json")), IoError);
}

TEST_CASE("viewer: PNG write then read returns the pixels") {
  Image img;
  img.width = 7, img.height = 5;
  img.rgba.resize(7 * 5 * 4);
  for (size_t k = 0; k < img.rgba.size(); ++k) img.rgba[k] = static_cast<std::uint8_t>((k * 37) % 256);
  const fs::path p = temp_file("img.png");
  write_png(p, img);
  const Image back = read_png(p);
  CHECK(back.width == 7);
  CHECK(back.height == 5);
  CHECK(back.rgba == img.rgba);
  Image bad;
  bad.width = 2, bad.height = 2;
  CHECK_THROWS_AS(write_png(p, bad), InvalidArgument);
  write(p, "not a png");
  CHECK_THROWS_AS(read_png(p), IoError);
}

TEST_CASE("viewer: an idle event (a replay barrier) survives a round trip and carries only its frame") {
  const fs::path p = temp_file("idle.json");
  write(p, R"({"format": "lapis-events", "width": 640, "height": 480, "events": [
    {"type": "move", "frame": 1, "x": 3, "y": 4}, {"type": "idle", "frame": 2}, {"type": "key", "frame": 2, "key": 67, "action": 1}]})");
  const EventLog log = EventLog::load(p);
  REQUIRE(log.events.size() == 3);
  CHECK(log.events[1].type == EventType::Idle);
  CHECK(log.events[1].frame == 2);
  log.save(p);
  const EventLog again = EventLog::load(p);
  CHECK(again.events[1].type == EventType::Idle);
  CHECK(std::string(to_string(EventType::Idle)) == "idle");
}
