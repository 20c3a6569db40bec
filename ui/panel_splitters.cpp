#include "ui/panel_splitters.h"

#include <imgui.h>

#include <algorithm>
#include <sstream>

#include "ui/settings_file.h"

namespace strata::ui {
namespace {

constexpr float kHandle = 6.0f;  // pixels: the grab strip of a splitter

// One handle: a small window over the strip (above the tiled panels, which never come to the
// front) holding an invisible button; returns the drag of this frame along `vertical` (x when
// true), and sets *ended when the drag was released.
float handle(const char* id, ImVec2 pos, ImVec2 size, bool vertical, bool* ended) {
  ImGui::SetNextWindowPos(pos);
  ImGui::SetNextWindowSize(size);
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(0, 0));
  ImGui::PushStyleVar(ImGuiStyleVar_WindowMinSize, ImVec2(1, 1));
  ImGui::Begin(id, nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoBackground |
                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                   ImGuiWindowFlags_NoNav);
  ImGui::InvisibleButton("##grip", size);
  float delta = 0.0f;
  const bool hot = ImGui::IsItemHovered() || ImGui::IsItemActive();
  if (hot) ImGui::SetMouseCursor(vertical ? ImGuiMouseCursor_ResizeEW : ImGuiMouseCursor_ResizeNS);
  if (ImGui::IsItemActive())
    delta = vertical ? ImGui::GetIO().MouseDelta.x : ImGui::GetIO().MouseDelta.y;
  if (ImGui::IsItemDeactivated()) *ended = true;
  if (hot) {
    ImGui::GetWindowDrawList()->AddRectFilled(
        pos, ImVec2(pos.x + size.x, pos.y + size.y),
        IM_COL32(240, 145, 45, ImGui::IsItemActive() ? 170 : 90));
  }
  ImGui::End();
  ImGui::PopStyleVar(2);
  return delta;
}

}  // namespace

void clampLayout(PanelLayout& layout, float width, float height) {
  const PanelSizes& wanted = layout.wanted;
  const float column = height - layout.menuHeight - layout.statusHeight;
  constexpr float kMinLeft = 200.0f, kMinRight = 240.0f;
  float left = std::clamp(wanted.leftWidth, kMinLeft, std::max(kMinLeft, width * 0.45f));
  float right = std::clamp(wanted.rightWidth, kMinRight, std::max(kMinRight, width * 0.45f));
  // In a narrow window both columns give up width in proportion (down to their minimums) so
  // that the view keeps at least 35% of it.
  const float room = 0.65f * width;
  if (left + right > room) {
    const float scale = room / (left + right);
    left = std::max(kMinLeft, left * scale);
    right = std::max(kMinRight, right * scale);
  }
  layout.leftWidth = left;
  layout.rightWidth = right;
  // The outliner keeps 120 px above the palette as drawn (its rows beyond paletteHeight too).
  layout.paletteHeight = std::clamp(wanted.paletteHeight, 120.0f,
                                    std::max(120.0f, column - 120.0f - layout.paletteRows));
  layout.previewHeight =
      std::clamp(wanted.previewHeight, 150.0f, std::max(150.0f, column - 120.0f));
}

bool drawSplitters(PanelLayout& layout) {
  const ImGuiViewport* vp = ImGui::GetMainViewport();
  const float top = vp->Pos.y + layout.menuHeight;
  const float bottom = vp->Pos.y + vp->Size.y - layout.statusHeight;
  const float column = bottom - top;
  bool ended = false;
  // A drag sets the size wanted from the size shown: the artist gets what they see.
  const auto drag = [](float delta, float shown, float* wanted) {
    if (delta != 0.0f) *wanted = shown + delta;
  };
  // Column edges: on the view's side of each edge (the view is not an ImGui window).
  drag(handle("##split left", ImVec2(vp->Pos.x + layout.leftWidth, top), ImVec2(kHandle, column),
              true, &ended),
       layout.leftWidth, &layout.wanted.leftWidth);
  drag(-handle("##split right", ImVec2(vp->Pos.x + vp->Size.x - layout.rightWidth - kHandle, top),
               ImVec2(kHandle, column), true, &ended),
       layout.rightWidth, &layout.wanted.rightWidth);
  // The palette's and the preview panel's top edges (the palette's as drawn: its rows beyond
  // layout.paletteHeight included; the handle sat inside it before).
  drag(
      -handle("##split palette", ImVec2(vp->Pos.x, bottom - paletteHeightFor(layout) - kHandle / 2),
              ImVec2(layout.leftWidth, kHandle), false, &ended),
      layout.paletteHeight, &layout.wanted.paletteHeight);
  drag(-handle("##split preview",
               ImVec2(vp->Pos.x + vp->Size.x - layout.rightWidth,
                      bottom - layout.previewHeight - kHandle / 2),
               ImVec2(layout.rightWidth, kHandle), false, &ended),
       layout.previewHeight, &layout.wanted.previewHeight);
  clampLayout(layout, vp->Size.x, vp->Size.y);
  return ended;
}

PanelLayout readPanelLayout(const std::string& path, PanelLayout layout) {
  readSettingLines(path, [&](const std::string& name, const std::string& text) {
    double number = 0.0;
    if (!settingNumber(text, &number) || !(number > 0.0) || number > 100000.0) return;
    const float value = float(number);
    if (name == "leftWidth") layout.wanted.leftWidth = value;
    if (name == "rightWidth") layout.wanted.rightWidth = value;
    if (name == "paletteHeight") layout.wanted.paletteHeight = value;
    if (name == "previewHeight") layout.wanted.previewHeight = value;
  });
  static_cast<PanelSizes&>(layout) = layout.wanted;
  return layout;
}

void writePanelLayout(const std::string& path, const PanelLayout& layout) {
  auto text = [](float v) {
    std::ostringstream out;
    out << v;
    return out.str();
  };
  writeSettingLines(path, {{"leftWidth", text(layout.wanted.leftWidth)},
                           {"rightWidth", text(layout.wanted.rightWidth)},
                           {"paletteHeight", text(layout.wanted.paletteHeight)},
                           {"previewHeight", text(layout.wanted.previewHeight)}});
}

}  // namespace strata::ui
