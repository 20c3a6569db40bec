#include "ui/theme.h"

#include <imgui.h>

#include <filesystem>

namespace strata::ui {
namespace {
bool g_unicode = false;

const char* findFont() {
  const char* candidates[] = {"/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
                              "/usr/share/fonts/TTF/DejaVuSans.ttf",
                              "/usr/share/fonts/dejavu/DejaVuSans.ttf"};
  for (const char* c : candidates) {
    std::error_code ec;
    if (std::filesystem::exists(c, ec)) return c;
  }
  return nullptr;
}
}  // namespace

void applyTheme(float scale) {
  ImGuiIO& io = ImGui::GetIO();
  if (const char* font = findFont()) {
    // File and part names in the languages DejaVu covers (Latin, Greek, Cyrillic), and the
    // symbols the panels use.
    static const ImWchar ranges[] = {0x0020, 0x024F,  // Latin-1, Latin Extended-A and -B
                                     0x0370, 0x03FF,  // Greek
                                     0x0400, 0x052F,  // Cyrillic
                                     0x2000, 0x206F,  // punctuation: … — ·
                                     0x2190, 0x21FF,  // arrows
                                     0x2200, 0x22FF,  // ∪ ∩ − ×
                                     0x2500, 0x25FF,  // box drawing, ● ○ ■ □ ▲
                                     0};
    if (io.Fonts->AddFontFromFileTTF(font, 15.0f * scale, nullptr, ranges)) g_unicode = true;
    // Chinese and Japanese names where a CJK font is installed (merged: DejaVu has none).
    const char* cjk[] = {"/usr/share/fonts/truetype/droid/DroidSansFallbackFull.ttf",
                         "/usr/share/fonts/opentype/noto/NotoSansCJK-Regular.ttc"};
    for (const char* c : cjk) {
      std::error_code ec;
      if (!g_unicode || !std::filesystem::exists(c, ec)) continue;
      ImFontConfig merge;
      merge.MergeMode = true;
      io.Fonts->AddFontFromFileTTF(c, 15.0f * scale, &merge,
                                   io.Fonts->GetGlyphRangesChineseSimplifiedCommon());
      break;
    }
  }
  if (!g_unicode) io.Fonts->AddFontDefault();

  ImGui::StyleColorsDark();
  ImGuiStyle& s = ImGui::GetStyle();
  s.WindowRounding = 0.0f;  // the panels tile the window, which is not cleared between frames
  s.PopupRounding = 4.0f;
  s.FrameRounding = 3.0f;
  s.GrabRounding = 3.0f;
  s.TabRounding = 3.0f;
  s.WindowBorderSize = 0.0f;
  s.FramePadding = ImVec2(6, 4);
  s.ItemSpacing = ImVec2(8, 5);
  s.IndentSpacing = 16.0f;
  ImVec4* c = s.Colors;
  c[ImGuiCol_WindowBg] = ImVec4(0.115f, 0.12f, 0.135f, 0.97f);
  c[ImGuiCol_ChildBg] = ImVec4(0.10f, 0.105f, 0.12f, 1.0f);
  c[ImGuiCol_PopupBg] = ImVec4(0.13f, 0.135f, 0.15f, 1.0f);  // tooltips and dialogs: opaque
  c[ImGuiCol_MenuBarBg] = ImVec4(0.09f, 0.095f, 0.105f, 1.0f);
  c[ImGuiCol_TitleBg] = ImVec4(0.09f, 0.095f, 0.105f, 1.0f);
  c[ImGuiCol_TitleBgActive] = ImVec4(0.11f, 0.12f, 0.14f, 1.0f);
  c[ImGuiCol_FrameBg] = ImVec4(0.18f, 0.19f, 0.215f, 1.0f);
  c[ImGuiCol_FrameBgHovered] = ImVec4(0.24f, 0.255f, 0.29f, 1.0f);
  c[ImGuiCol_FrameBgActive] = ImVec4(0.28f, 0.30f, 0.34f, 1.0f);
  const ImVec4 accent(0.95f, 0.56f, 0.18f, 1.0f);
  c[ImGuiCol_Header] = ImVec4(0.95f, 0.56f, 0.18f, 0.30f);
  // Hover is a neutral grey-blue, selection orange: the two never look alike.
  c[ImGuiCol_HeaderHovered] = ImVec4(0.55f, 0.62f, 0.75f, 0.22f);
  c[ImGuiCol_HeaderActive] = ImVec4(0.95f, 0.56f, 0.18f, 0.60f);
  c[ImGuiCol_Button] = ImVec4(0.21f, 0.225f, 0.255f, 1.0f);
  c[ImGuiCol_ButtonHovered] = ImVec4(0.95f, 0.56f, 0.18f, 0.55f);
  c[ImGuiCol_ButtonActive] = ImVec4(0.95f, 0.56f, 0.18f, 0.80f);
  c[ImGuiCol_CheckMark] = accent;
  c[ImGuiCol_SliderGrab] = accent;
  c[ImGuiCol_SliderGrabActive] = ImVec4(1.0f, 0.68f, 0.3f, 1.0f);
  c[ImGuiCol_PlotHistogram] = accent;
  c[ImGuiCol_DragDropTarget] = ImVec4(1.0f, 0.75f, 0.2f, 0.9f);
  c[ImGuiCol_Separator] = ImVec4(0.22f, 0.23f, 0.26f, 1.0f);
  // Behind a modal dialog the editor darkens (the dark style's light grey turned the view near
  // white behind the export's file dialog, a modal over a modal: an artist's test).
  c[ImGuiCol_ModalWindowDimBg] = ImVec4(0.0f, 0.0f, 0.0f, 0.30f);
  c[ImGuiCol_NavWindowingDimBg] = ImVec4(0.0f, 0.0f, 0.0f, 0.30f);
  s.ScaleAllSizes(scale);
}

const char* kindGlyph(NodeKind kind) {
  const NodeKindInfo& info = nodeKindInfo(kind);
  return g_unicode ? info.glyph : info.asciiGlyph;
}

std::vector<bool> operationRowStarts(const std::vector<NodeKind>& ops, int perRow) {
  auto family = [](NodeKind k) {
    return modifierOf(k) != Modifier::None ? 1 : patternOf(k) != Pattern::None ? 2 : 0;
  };
  std::vector<bool> starts(ops.size(), false);
  int inRow = 0;
  for (size_t i = 0; i < ops.size(); ++i) {
    starts[i] = i == 0 || family(ops[i]) != family(ops[i - 1]) || inRow == perRow;
    inRow = starts[i] ? 1 : inRow + 1;
  }
  return starts;
}

const char* visibleGlyph(bool visible) {
  if (!g_unicode) return visible ? "o" : "-";
  return visible ? "\u25C9" : "\u25CB";  // ◉ ○
}

}  // namespace strata::ui
