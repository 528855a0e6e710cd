#include "lapis/viewer/input_events.h"

#include <fstream>
#include <nlohmann/json.hpp>

#include "lapis/core/atomic_file.h"
#include "lapis/core/checked_number.h"
#include "lapis/core/error.h"

namespace lapis::viewer {
namespace {

constexpr EventType kTypes[] = {EventType::MouseMove, EventType::MouseButton, EventType::Scroll, EventType::Key,
                                EventType::Char,      EventType::Resize,      EventType::Idle};

EventType parse_type(const std::string& s, const std::string& where) {
  for (EventType t : kTypes)
    if (s == to_string(t)) return t;
  throw IoError(where + ": unknown event type '" + s + "'");
}

}  // namespace

const char* to_string(EventType t) {
  switch (t) {
    case EventType::MouseMove:
      return "move";
    case EventType::MouseButton:
      return "button";
    case EventType::Scroll:
      return "scroll";
    case EventType::Key:
      return "key";
    case EventType::Char:
      return "char";
    case EventType::Resize:
      return "resize";
    case EventType::Idle:
      return "idle";
  }
  return "?";
}

void EventLog::save(const std::filesystem::path& path) const {
  nlohmann::json j;
  j["format"] = "lapis-events";
  j["version"] = 1;
  j["width"] = width;
  j["height"] = height;
  auto& list = j["events"] = nlohmann::json::array();
  for (const InputEvent& e : events) {
    nlohmann::json o = {{"type", to_string(e.type)}, {"frame", e.frame}, {"time", e.time}};
    switch (e.type) {
      case EventType::MouseMove:
        o["x"] = e.x, o["y"] = e.y;
        break;
      case EventType::MouseButton:
        o["x"] = e.x, o["y"] = e.y, o["button"] = e.button, o["action"] = e.action, o["mods"] = e.mods;
        break;
      case EventType::Scroll:
        o["x"] = e.x, o["y"] = e.y;
        break;
      case EventType::Key:
        o["key"] = e.key, o["action"] = e.action, o["mods"] = e.mods;
        break;
      case EventType::Char:
        o["codepoint"] = e.codepoint;
        break;
      case EventType::Resize:
        o["width"] = e.width, o["height"] = e.height;
        break;
      case EventType::Idle:
        break;
    }
    list.push_back(std::move(o));
  }
  core::write_file_atomically(path, [&](std::ostream& out) { out << j.dump(1) << "\n"; });
}

EventLog EventLog::load(const std::filesystem::path& path) {
  const std::string fn = "viewer::EventLog::load(): " + path.string();
  std::ifstream in(path);
  if (!in) throw IoError(fn + ": cannot open file");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw IoError(fn + ": not valid JSON (" + e.what() + ")");
  }
  EventLog log;
  try {
    if (j.value("format", "") != "lapis-events") throw IoError(fn + ": 'format' is not \"lapis-events\"");
    log.width = static_cast<int>(json_integer<IoError>(j.at("width"), fn + ": width", 0, 1 << 16));
    log.height = static_cast<int>(json_integer<IoError>(j.at("height"), fn + ": height", 0, 1 << 16));
    const auto& list = j.at("events");
    if (!list.is_array()) throw IoError(fn + ": 'events' is not an array");
    long last_frame = 0;
    for (size_t k = 0; k < list.size(); ++k) {
      const auto& o = list[k];
      const std::string where = fn + ": event " + std::to_string(k);
      InputEvent e;
      e.type = parse_type(o.at("type").get<std::string>(), where);
      // Optional fields: a missing key reads as 0, a present one must be in range.
      const auto number = [&](const char* k, double lo, double hi) {
        return o.contains(k) ? json_finite<IoError>(o[k], where + ": " + k, lo, hi) : 0.0;
      };
      const auto integer = [&](const char* k, long long lo, long long hi) {
        return o.contains(k) ? json_integer<IoError>(o[k], where + ": " + k, lo, hi) : 0;
      };
      e.frame = static_cast<long>(json_integer<IoError>(o.at("frame"), where + ": frame", 0, LONG_MAX));
      e.time = number("time", 0, kAnyFinite);
      if (e.frame < last_frame) throw IoError(where + ": frame " + std::to_string(e.frame) + " goes backwards");
      last_frame = e.frame;
      e.x = number("x", -kAnyFinite, kAnyFinite);
      e.y = number("y", -kAnyFinite, kAnyFinite);
      e.button = static_cast<int>(integer("button", INT_MIN, INT_MAX));
      e.action = static_cast<int>(integer("action", INT_MIN, INT_MAX));
      e.mods = static_cast<int>(integer("mods", INT_MIN, INT_MAX));
      e.key = static_cast<int>(integer("key", INT_MIN, INT_MAX));
      e.codepoint = static_cast<unsigned>(integer("codepoint", 0, 0x10FFFF));
      e.width = static_cast<int>(integer("width", 0, 1 << 16));
      e.height = static_cast<int>(integer("height", 0, 1 << 16));
      log.events.push_back(e);
    }
  } catch (const nlohmann::json::exception& e) {
    throw IoError(fn + ": malformed event log (" + e.what() + ")");
  }
  return log;
}

}  // namespace lapis::viewer
