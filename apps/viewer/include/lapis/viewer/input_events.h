// The stream of mouse and keyboard events an app receives, with the frame and time each
// arrived at. Recorded to a JSON file and replayed frame by frame, so any interaction can
// be reproduced exactly (tests, bug reports, benchmarks, documentation screenshots).
#pragma once

#include <filesystem>

#include <string>
#include <vector>
#include "lapis/core/error.h"

namespace lapis::viewer {

// Idle is never recorded: written into a log by hand or a generator, it holds the replay until
// the app is no longer busy (a setup finished), and the events after it keep their spacing.
enum class EventType { MouseMove, MouseButton, Scroll, Key, Char, Resize, Idle };

struct InputEvent {
  EventType type = EventType::MouseMove;
  long frame = 0;       // frame index at which the event arrived
  double time = 0;      // seconds since the app started
  double x = 0, y = 0;  // cursor position in pixels (y down); scroll offsets for Scroll
  int button = 0;       // GLFW_MOUSE_BUTTON_*
  int action = 0;       // GLFW_PRESS / GLFW_RELEASE / GLFW_REPEAT
  int mods = 0;         // GLFW_MOD_* bits
  int key = 0;          // GLFW_KEY_*
  unsigned codepoint = 0;
  int width = 0, height = 0;  // Resize
};

const char* to_string(EventType t);

struct EventLog {
  std::vector<InputEvent> events;
  int width = 0, height = 0;  // window size when recorded (replays use it)

  // Atomic write; throws IoError.
  void save(const std::filesystem::path& path) const;
  // Throws IoError naming the file and the event index on malformed content.
  static EventLog load(const std::filesystem::path& path);
};

}  // namespace lapis::viewer
