#include "lapis/viewer/panel_column.h"

#include <algorithm>

#include <imgui.h>

namespace lapis::viewer {

bool PanelColumn::begin(const char* title, int flags) {
  const float x = window_width_ - width_ - 10;
  // Every panel keeps at least its title bar on screen, and those under it theirs.
  remaining_ = std::max(remaining_ - 1, 0);
  const float bar = ImGui::GetFrameHeight() + gap_, below = static_cast<float>(remaining_) * bar;
  const float y = std::min(next_y_, window_height_ - 10 - below - bar);
  ImGui::SetNextWindowPos(ImVec2(x, y), ImGuiCond_Always);
  ImGui::SetNextWindowSizeConstraints(ImVec2(width_, 0),
                                      ImVec2(width_, std::max(bar, window_height_ - 10 - below - y)));
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
