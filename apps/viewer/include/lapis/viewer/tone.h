// What a message tells the user, and the one colour each kind has in every app, so that an
// error never looks like a confirmation: plain status, success (saved, exported), a warning
// (the work goes on, but look), an error (the action did not happen).
#pragma once

#include <string>

namespace lapis::viewer {

enum class Tone { Status, Success, Warning, Error };

// Draws `text` in the current ImGui window in its tone's colour, wrapped where the window's
// local x reaches `wrap_at` (0: at its right edge, which an auto-resizing window of no fixed
// width never widens past).
void tone_text(Tone tone, const std::string& text, float wrap_at = 0.0f);

}  // namespace lapis::viewer
