#include "lapis/viewer/panel_column.h"

#include <algorithm>

#include <imgui.h>

namespace lapis::viewer {

bool PanelColumn::begin(const char* title, int flags) {
  const float x = window_width_ - width_ - 10;
  // A collapsed or far-down column still leaves every panel a title bar's height on screen.
  const float y = std::min(next_y_, window_height_ - 40);
  ImGui::SetNextWindowPos(ImVec2(x, y), ImGuiCond_Always);
  ImGui::SetNextWindowSizeConstraints(ImVec2(width_, 0), ImVec2(width_, std::max(40.0f, window_height_ - y - 10)));
  const bool open = ImGui::Begin(title, nullptr, flags | ImGuiWindowFlags_AlwaysAutoResize);
  // Half the width for the widgets, half for their labels (ImGui's default, 65% for the widget,
  // cut labels such as "iterations / frame" at this width).
  ImGui::PushItemWidth(0.5f * width_);
  return open;
}

void PanelColumn::end() {
  ImGui::PopItemWidth();
  next_y_ = ImGui::GetWindowPos().y + ImGui::GetWindowSize().y + gap_;
  ImGui::End();
}

}  // namespace lapis::viewer
