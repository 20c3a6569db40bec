// See typed_value.h.
#include "ui/typed_value.h"

#include <imgui.h>
#include <imgui_internal.h>  // TempInputIsActive: is the last item a drag field typing text?

namespace strata::ui {
namespace {

// The field being typed into, its last value and the last frame it was seen typing; one at a
// time (one item is active).
struct Typed {
  ImGuiID id = 0;
  double value = 0.0;
  int frame = 0;
  bool held = false;
};
Typed gTyped;

template <class T>
bool commit(bool changed, T* value) {
  const ImGuiID id = ImGui::GetItemID();
  if (id != 0 && ImGui::TempInputIsActive(id)) {
    if (gTyped.id != id) gTyped = {id, double(*value), 0, false};
    if (changed) gTyped.value = double(*value), gTyped.held = true;
    gTyped.frame = ImGui::GetFrameCount();
    return false;
  }
  if (!gTyped.held || gTyped.id != id) return changed;
  // The field was left on this frame (it typed on the last): the typed value, unless Escape took
  // it back. A value held by a field that was not drawn since (its node deselected) is dropped.
  gTyped.held = false;
  if (gTyped.frame != ImGui::GetFrameCount() - 1) return changed;
  if (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape), false)) return false;
  if (!changed) *value = T(gTyped.value);
  return true;
}

}  // namespace

bool doubleClickOpensTyping(double before, double* beforePress) {
  static ImGuiID pressedId = 0;  // the slider last pressed (not by a double-click's second press)
  static double atPress = 0.0;
  const ImGuiID id = ImGui::GetItemID();
  if (ImGui::IsItemActivated() && !ImGui::IsMouseDoubleClicked(0)) pressedId = id, atPress = before;
  if (!ImGui::IsItemHovered() || !ImGui::IsMouseDoubleClicked(0)) return false;
  ImGui::SetKeyboardFocusHere(-1);
  *beforePress = pressedId == id ? atPress : before;
  return true;
}

bool typingIntoNumberField() {
  const ImGuiContext* g = ImGui::GetCurrentContext();
  return g && g->ActiveId != 0 && g->TempInputId == g->ActiveId;
}

unsigned numberFieldCharacter(unsigned codepoint, std::string* dropped) {
  if (!typingIntoNumberField()) return codepoint;
  if (codepoint == ',') return '.';
  const bool kept = (codepoint >= '0' && codepoint <= '9') || codepoint == '.' ||
                    codepoint == '+' || codepoint == '-' || codepoint == '*' || codepoint == '/' ||
                    codepoint == 'e' || codepoint == 'E';
  if (!kept && codepoint != ' ' && codepoint < 128) dropped->push_back(char(codepoint));
  return codepoint;
}

bool commitTypedValue(bool changed, double* value) {
  return commit(changed, value);
}
bool commitTypedValue(bool changed, int* value) {
  return commit(changed, value);
}

}  // namespace strata::ui
