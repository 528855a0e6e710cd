#include "lapis/viewer/tone.h"

#include <imgui.h>

namespace lapis::viewer {
namespace {

ImVec4 tone_color(Tone tone) {
  switch (tone) {
    case Tone::Success:
      return ImVec4(0.45f, 0.95f, 0.5f, 1.0f);
    case Tone::Warning:
      return ImVec4(1.0f, 0.8f, 0.3f, 1.0f);
    case Tone::Error:
      return ImVec4(1.0f, 0.42f, 0.32f, 1.0f);
    case Tone::Status:
      break;
  }
  return ImGui::GetStyleColorVec4(ImGuiCol_Text);
}

}  // namespace

void tone_text(Tone tone, const std::string& text, float wrap_at) {
  ImGui::PushStyleColor(ImGuiCol_Text, tone_color(tone));
  ImGui::PushTextWrapPos(wrap_at);
  ImGui::TextUnformatted(text.c_str());
  ImGui::PopTextWrapPos();
  ImGui::PopStyleColor();
}

}  // namespace lapis::viewer
