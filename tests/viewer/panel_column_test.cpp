// The right-hand panel column, laid out by Dear ImGui itself (a context without a display):
// panels stack without overlapping, follow their content's height both ways (a method switch
// that hides controls shrinks its panel) and never run past the window's bottom.
#include <doctest/doctest.h>

#include <imgui.h>
#include <imgui_internal.h>

#include <string>
#include <vector>

#include "lapis/viewer/panel_column.h"

using namespace lapis::viewer;

namespace {

struct Rect {
  float top, bottom;
  float scroll_max;
};

// Lays out one frame of panels holding `lines[i]` lines of text; returns their rectangles.
std::vector<Rect> frame(const std::vector<int>& lines, float width, float height) {
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(width, height);
  io.DeltaTime = 1.0f / 60;
  ImGui::NewFrame();
  PanelColumn column(width, height, 300, static_cast<int>(lines.size()));
  std::vector<Rect> out;
  for (size_t p = 0; p < lines.size(); ++p) {
    const std::string title = "panel " + std::to_string(p);
    column.begin(title.c_str());
    for (int k = 0; k < lines[p]; ++k) ImGui::Text("line %d", k);
    const ImGuiWindow* w = ImGui::GetCurrentWindow();
    out.push_back({w->Pos.y, w->Pos.y + w->Size.y, w->ScrollMax.y});
    column.end();
  }
  ImGui::EndFrame();
  return out;
}

// ImGui sizes an auto-resizing window from the previous frame's content: a few frames settle it.
std::vector<Rect> settled(const std::vector<int>& lines, float width, float height) {
  std::vector<Rect> r;
  for (int k = 0; k < 4; ++k) r = frame(lines, width, height);
  return r;
}

}  // namespace

TEST_CASE("viewer: the panel column stacks its panels, sizes them to their content and keeps them on screen") {
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini left in the working directory
  unsigned char* pixels = nullptr;
  int w = 0, h = 0;
  ImGui::GetIO().Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);  // builds the font atlas

  const float height = 600;
  std::vector<Rect> r = settled({5, 3, 4}, 1000, height);
  REQUIRE(r.size() == 3);
  for (size_t p = 1; p < r.size(); ++p) CHECK(r[p].top == doctest::Approx(r[p - 1].bottom + 6));
  const float short_first = r[0].bottom - r[0].top;

  // A panel that grows (a second handle, another method's controls) pushes the next ones down.
  r = settled({12, 3, 4}, 1000, height);
  CHECK(r[0].bottom - r[0].top > short_first + 50);
  CHECK(r[1].top == doctest::Approx(r[0].bottom + 6));
  // And shrinks back when its content does: no first-height memory.
  r = settled({5, 3, 4}, 1000, height);
  CHECK(r[0].bottom - r[0].top == doctest::Approx(short_first));

  // More than fits: the one cut short scrolls, the panels still do not overlap, and each ends
  // above the window's bottom.
  r = settled({5, 80, 4}, 1000, height);
  CHECK(r[1].scroll_max > 0);
  for (size_t p = 1; p < r.size(); ++p) CHECK(r[p].top >= r[p - 1].bottom);
  for (const Rect& p : r) CHECK(p.bottom <= height);
  ImGui::DestroyContext();
}
