// The shortcut sheet (F1, Help > Shortcuts): every key and mouse gesture of the editor in one
// window, grouped as the menus are. The keys themselves are handled where they act
// (main_menu.cpp, viewport.cpp, panel_outliner.cpp); this list is kept beside them.
#include <imgui.h>

#include <initializer_list>

#include "ui/panels.h"

namespace strata::ui {
namespace {

struct Shortcut {
  const char* keys;
  const char* what;
};

struct ShortcutGroup {
  const char* title;
  std::initializer_list<Shortcut> items;
};

const ShortcutGroup kGroups[] = {
    {"Files",
     {{"Ctrl+N", "new document"},
      {"Ctrl+O", "open"},
      {"Ctrl+S / Ctrl+Shift+S", "save / save as"},
      {"Ctrl+E", "export a watertight mesh"},
      {"Ctrl+Q", "quit (asks about unsaved changes and a running export)"}}},
    {"Edit",
     {{"Ctrl+Z / Ctrl+Y", "undo / redo (Ctrl+Shift+Z too)"},
      {"Ctrl+C / Ctrl+X / Ctrl+V",
       "copy / cut / paste onto the selection (copies keep their role; a copy lands a grid step "
       "along +x from its original, a cut part back where it was, in its parent)"},
      {"Ctrl+D", "duplicate: the copy does what the original does, one grid step along +x"},
      {"Alt+D", "instance: a live copy"},
      {"Del", "delete"},
      {"H", "hide / show"},
      {"F2, double-click", "rename"},
      {"Ctrl+G",
       "group parts that do the same (a union; for parts that intersect, an intersection)"},
      {"Esc", "call off a gizmo drag; close a menu or this sheet; select none"}}},
    {"Number fields (inspector, preview)",
     {{"drag left / right", "change the value (a coarser preview while dragging)"},
      {"double-click, Ctrl+click", "type a number"},
      {"Enter, Tab, a click elsewhere", "apply the typed number (Tab: to the next field)"},
      {"Esc while typing", "keep the old value"},
      {"9,5 or 9.5", "the same number"},
      {"1cm, 2 in, 0.5 m", "a length typed with a unit is converted into the scene's unit"}}},
    {"Placing parts: add, cut or intersect",
     {{"palette mode", "what a new part from the palette does"},
      {"drag from the palette onto a part",
       "onto that part (in the view: the part under the "
       "pointer; on the ground: onto the selection)"},
      {"dropped on a surface",
       "an added part rests on it (and stays on it when resized); a cutter is centred on the "
       "point"},
      {"drag a row onto a row",
       "moves the part: a hole stays a hole, a solid takes no material away (its role changes "
       "where the place needs it); onto a modifier's or a pattern's row, a solid goes into it (it "
       "is "
       "shelled, rounded or repeated with its parts); the tooltip says what it will do"},
      {"Ctrl while dropping", "cuts"},
      {"Shift while dropping", "intersects"},
      {"Alt while dropping", "adds"}}},
    {"Select",
     {{"click", "select a part (in the view or the tree)"},
      {"Ctrl+click", "add or remove one"},
      {"Shift+click (tree)", "select a range"},
      {"drag on empty space", "box select (Shift/Ctrl: add)"}}},
    {"View",
     {{"middle drag, Alt+left drag", "orbit"},
      {"Shift+middle drag", "pan"},
      {"wheel", "zoom about the point under the cursor"},
      {"F / Home", "frame the selection / everything"},
      {"1 3 7 (Ctrl: opposite)", "front, right, top"},
      {"5", "orthographic / perspective"},
      {"G", "ghosts of every part that cuts or intersects"},
      {"W E R", "move, rotate, scale gizmo"},
      {"M",
       "measure: two clicks a distance, a third the angle; Esc ends; they stay until "
       "Edit > Clear measurements (one at a time: View > Diagnostics)"},
      {"F1", "this sheet"}}},
};

}  // namespace

void drawShortcutSheet(EditorState& state) {
  if (!state.showShortcuts) return;
  const ImGuiViewport* vp = ImGui::GetMainViewport();
  ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + vp->Size.x * 0.5f, vp->Pos.y + vp->Size.y * 0.5f),
                          ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowSize(ImVec2(560.0f, 0.0f), ImGuiCond_Appearing);
  if (!ImGui::Begin("Shortcuts (F1)", &state.showShortcuts,
                    ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoSavedSettings)) {
    ImGui::End();
    return;
  }
  for (const ShortcutGroup& group : kGroups) {
    ImGui::TextColored(ImVec4(0.95f, 0.62f, 0.25f, 1.0f), "%s", group.title);
    if (ImGui::BeginTable(group.title, 2)) {
      // The same key column in every group, so that the sheet reads as one table.
      ImGui::TableSetupColumn("keys", ImGuiTableColumnFlags_WidthFixed, 220.0f);
      ImGui::TableSetupColumn("what", ImGuiTableColumnFlags_WidthStretch);
      for (const Shortcut& s : group.items) {
        ImGui::TableNextRow();
        ImGui::TableSetColumnIndex(0);
        ImGui::TextUnformatted(s.keys);
        ImGui::TableSetColumnIndex(1);
        ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
        ImGui::TextWrapped("%s", s.what);  // a long line wraps in its column, never cut
        ImGui::PopStyleColor();
      }
      ImGui::EndTable();
    }
    ImGui::Spacing();
  }
  ImGui::End();
}

}  // namespace strata::ui
