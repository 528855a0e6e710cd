#include "lapis/viewer/input_events.h"

#include <fstream>
#include <nlohmann/json.hpp>

#include "lapis/core/error.h"
#include "lapis/geometry/atomic_file.h"

namespace lapis::viewer {
namespace {

constexpr EventType kTypes[] = {EventType::MouseMove, EventType::MouseButton, EventType::Scroll,
                                EventType::Key, EventType::Char, EventType::Resize, EventType::Idle};

EventType parse_type(const std::string& s, const std::string& where) {
  for (EventType t : kTypes)
    if (s == to_string(t)) return t;
  throw IoError(where + ": unknown event type '" + s + "'");
}

}  // namespace

const char* to_string(EventType t) {
  switch (t) {
    case EventType::MouseMove: return "move";
    case EventType::MouseButton: return "button";
    case EventType::Scroll: return "scroll";
    case EventType::Key: return "key";
    case EventType::Char: return "char";
    case EventType::Resize: return "resize";
    case EventType::Idle: return "idle";
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
      case EventType::MouseMove: o["x"] = e.x, o["y"] = e.y; break;
      case EventType::MouseButton: o["x"] = e.x, o["y"] = e.y, o["button"] = e.button, o["action"] = e.action, o["mods"] = e.mods; break;
      case EventType::Scroll: o["x"] = e.x, o["y"] = e.y; break;
      case EventType::Key: o["key"] = e.key, o["action"] = e.action, o["mods"] = e.mods; break;
      case EventType::Char: o["codepoint"] = e.codepoint; break;
      case EventType::Resize: o["width"] = e.width, o["height"] = e.height; break;
      case EventType::Idle: break;
    }
    list.push_back(std::move(o));
  }
  geometry::write_file_atomically(path, [&](std::ostream& out) { out << j.dump(1) << "\n"; });
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
    log.width = j.at("width").get<int>();
    log.height = j.at("height").get<int>();
    const auto& list = j.at("events");
    if (!list.is_array()) throw IoError(fn + ": 'events' is not an array");
    long last_frame = 0;
    for (size_t k = 0; k < list.size(); ++k) {
      const auto& o = list[k];
      const std::string where = fn + ": event " + std::to_string(k);
      InputEvent e;
      e.type = parse_type(o.at("type").get<std::string>(), where);
      e.frame = o.at("frame").get<long>();
      e.time = o.value("time", 0.0);
      if (e.frame < last_frame) throw IoError(where + ": frame " + std::to_string(e.frame) + " goes backwards");
      last_frame = e.frame;
      e.x = o.value("x", 0.0);
      e.y = o.value("y", 0.0);
      e.button = o.value("button", 0);
      e.action = o.value("action", 0);
      e.mods = o.value("mods", 0);
      e.key = o.value("key", 0);
      e.codepoint = o.value("codepoint", 0u);
      e.width = o.value("width", 0);
      e.height = o.value("height", 0);
      if (!std::isfinite(e.x) || !std::isfinite(e.y)) throw IoError(where + ": non-finite coordinates");
      log.events.push_back(e);
    }
  } catch (const nlohmann::json::exception& e) {
    throw IoError(fn + ": malformed event log (" + e.what() + ")");
  }
  return log;
}

}  // namespace lapis::viewer
