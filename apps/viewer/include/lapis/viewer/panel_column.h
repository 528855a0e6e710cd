// Panels stacked down the window's right edge, each under the one before it, each as tall as
// its content (a method switch or a new handle re-sizes it) and never past the window's bottom:
// a panel that does not fit scrolls. The column places its panels every frame, so they do not
// overlap; a user collapses one to make room. Used once per frame: begin()/end() around each
// panel, in order.
#pragma once

namespace lapis::viewer {

class PanelColumn {
 public:
  // `panels`: how many begin()s follow, so a panel cut short leaves the ones under it room for
  // their title bars.
  PanelColumn(float window_width, float window_height, float panel_width, int panels, float top = 10, float gap = 6)
      : window_width_(window_width),
        window_height_(window_height),
        width_(panel_width),
        next_y_(top),
        gap_(gap),
        remaining_(panels) {}

  // ImGui::Begin(title) at the column's next slot, with half the panel's width for widgets and
  // half for their labels; `flags` are ImGuiWindowFlags added to the column's own. Returns what
  // ImGui::Begin returns; call end() either way.
  bool begin(const char* title, int flags = 0);
  void end();  // ImGui::End(), and the next panel goes under this one

 private:
  float window_width_, window_height_, width_, next_y_, gap_;
  int remaining_;
};

}  // namespace lapis::viewer
