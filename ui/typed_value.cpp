// See typed_value.h.
#include "ui/typed_value.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include <imgui.h>
#include <imgui_internal.h>  // TempInputIsActive: is the last item a drag field typing text?

#include "ui/import_options.h"

namespace strata::ui {
namespace {

// The field being typed into, its last value and the last frame it was seen typing; one at a
// time (one item is active).
struct Typed {
  ImGuiID id = 0;
  double value = 0.0;
  int frame = 0;
  bool held = false;
  std::string text;  // the field's text on the last frame seen
};
Typed gTyped;

// The text of field `id` being typed into (Dear ImGui's input state), "" for another field.
std::string typedText(ImGuiID id) {
  const ImGuiInputTextState& field = ImGui::GetCurrentContext()->InputTextState;
  if (field.ID != id) return "";
  char text[128] = "";
  ImTextStrToUtf8(text, int(sizeof(text)), field.TextW.Data, field.TextW.Data + field.CurLenW);
  return text;
}

// The letters numberFieldCharacter dropped from the field being typed (ImGui id), and what the
// last commit converted (takeUnitConversion).
struct Dropped {
  ImGuiID id = 0;
  std::string letters;
  double since = 0.0;        // when the field's typing began (ImGui time): letters of one typing
  bool numberAfter = false;  // a digit or a point typed after the letters: no unit of the number
  bool spaceAfterNumber = false;  // a space typed right after a digit or a point
  bool twoNumbers = false;        // then a digit or a point: "15 5", which the field shows as 155
};
Dropped gDropped;
std::string gConversion;
bool gConverted = false;  // since takeUnitConverted
std::string gRefusal;     // takeTypedRefusal

// What letters typed with a number (spaces left out) make of it, in a field whose unit is
// `lengthUnit` ("" for a field that is no length): the one rule both the hint under the field
// (showDroppedLetters) and the commit (convertTypedUnit) read.
enum class Letters {
  None,          // none typed
  Converts,      // a length unit, in a length field: converted into the field's unit
  Degrees,       // the degree sign, in a field that is no length: the number as typed
  BeforeNumber,  // letters before a number ("1 cm 2"): no unit of it
  NotALength,    // a length unit (or letters) in a field that is no length
  NoUnit,        // letters that name no unit, in a length field
};
Letters judgeLetters(const std::string& letters, bool numberAfter, const std::string& lengthUnit) {
  if (letters.empty()) return Letters::None;
  if (numberAfter) return Letters::BeforeNumber;
  if (lengthUnit.empty()) return letters == "\u00B0" ? Letters::Degrees : Letters::NotALength;
  return sceneUnitMetres(letters) > 0.0 && sceneUnitMetres(lengthUnit) > 0.0 ? Letters::Converts
                                                                             : Letters::NoUnit;
}

// The typed value in `lengthUnit` where the letters typed into field `id` name a length unit
// ("cm" typed into a mm field: times 10); `value` where none were typed (or a field that is no
// length got its degrees); none where the letters make no sense of the number: no unit, a length
// unit in a field that is no length, or letters before a number ("1 cm 2": the field shows 12).
// Such a number is not applied: the field keeps its value (an artist's re-test: "3 xyz" gave 3 mm
// and "1 cm 2" 12 mm, said only as letters not typed).
std::optional<double> convertTypedUnit(ImGuiID id, double value, const std::string& lengthUnit) {
  if (gDropped.id != id) return value;
  std::string typed;
  for (char c : gDropped.letters)
    if (c != ' ') typed += c;
  const Letters verdict = judgeLetters(typed, gDropped.numberAfter, lengthUnit);
  gDropped = {};
  if (verdict == Letters::None) return value;
  if (verdict == Letters::Degrees) {
    gConverted = true;  // its letters were understood: not said as letters not typed
    return value;
  }
  if (verdict != Letters::Converts) return std::nullopt;
  const double from = sceneUnitMetres(typed), to = sceneUnitMetres(lengthUnit);
  const double converted = value * (from / to);
  char text[160];
  std::snprintf(text, sizeof(text), "%.6g %s is %.6g %s", value, typed.c_str(), converted,
                lengthUnit.c_str());
  gConversion = text;
  gConverted = true;
  return converted;
}

std::string gHintShown;  // showDroppedLetters' line on the last frame it drew one (tests)

// Draws `line` as a tooltip under the last item (the field being typed into).
void hintBelowField(const char* line);

// While field `id` (the last item) is being typed: the letters it dropped drawn after its text,
// inside its frame and dimmed, so that "1cm" reads as typed (the field shows "1"), and under it
// what they will do when the field is left. Nothing where it dropped none.
void showDroppedLetters(ImGuiID id, const std::string& lengthUnit) {
  std::string letters;
  for (char c : gDropped.letters)
    if (c != ' ') letters += c;
  if (gDropped.id != id || letters.empty()) return;
  const ImGuiContext& g = *ImGui::GetCurrentContext();
  const ImGuiInputTextState& field = g.InputTextState;
  if (field.ID != id) return;
  char typed[128] = "";
  ImTextStrToUtf8(typed, int(sizeof(typed)), field.TextW.Data, field.TextW.Data + field.CurLenW);
  const ImGuiStyle& style = ImGui::GetStyle();
  const ImVec2 min = ImGui::GetItemRectMin(), max = ImGui::GetItemRectMax();
  const float x = min.x + style.FramePadding.x + ImGui::CalcTextSize(typed).x - field.ScrollX +
                  ImGui::CalcTextSize(" ").x;
  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->PushClipRect(min, max, true);
  draw->AddText(ImVec2(x, min.y + style.FramePadding.y), ImGui::GetColorU32(ImGuiCol_TextDisabled),
                letters.c_str());
  draw->PopClipRect();
  // What leaving the field will make of them.
  const Letters verdict = judgeLetters(letters, gDropped.numberAfter, lengthUnit);
  if (verdict == Letters::Degrees) return;  // an angle's degrees: nothing to say
  char line[200];
  char* end = nullptr;
  const double number = std::strtod(typed, &end);
  const bool plain = end != typed && *end == '\0' && std::isfinite(number);
  if (verdict == Letters::BeforeNumber)
    std::snprintf(line, sizeof(line),
                  "\"%s\" before a number is no unit: leaving the field changes nothing",
                  letters.c_str());
  else if (verdict == Letters::Converts && plain)
    std::snprintf(
        line, sizeof(line), "%.6g %s: %.6g %s when the field is left", number, letters.c_str(),
        number * (sceneUnitMetres(letters) / sceneUnitMetres(lengthUnit)), lengthUnit.c_str());
  else if (verdict == Letters::Converts)
    std::snprintf(line, sizeof(line), "%s: converted into %s when the field is left",
                  letters.c_str(), lengthUnit.c_str());
  else if (verdict == Letters::NotALength)
    std::snprintf(line, sizeof(line), "\"%s\": this field is no length: leaving it changes nothing",
                  letters.c_str());
  else
    std::snprintf(line, sizeof(line),
                  "\"%s\" is no unit (mm, cm, m, in, ft): leaving the field changes nothing",
                  letters.c_str());
  hintBelowField(line);
}

void hintBelowField(const char* line) {
  const ImGuiContext& g = *ImGui::GetCurrentContext();
  const ImGuiStyle& style = ImGui::GetStyle();
  const ImVec2 min = ImGui::GetItemRectMin(), max = ImGui::GetItemRectMax();
  gHintShown = line;
  // Below the field, within the window (it ran off the screen's edge beside the right panel's
  // fields: an artist's re-test).
  const float width = ImGui::CalcTextSize(line).x + 2.0f * style.WindowPadding.x;
  const float right = ImGui::GetMainViewport()->Pos.x + ImGui::GetMainViewport()->Size.x;
  ImGui::SetNextWindowPos(ImVec2(std::max(0.0f, std::min(min.x, right - width)), max.y + 2.0f));
  // In the theme's text colour, not the one the field may have pushed (an axis's red).
  ImVec4 text = g.Style.Colors[ImGuiCol_Text];
  for (int i = g.ColorStack.Size - 1; i >= 0; --i)
    if (g.ColorStack[i].Col == ImGuiCol_Text) text = g.ColorStack[i].BackupValue;
  ImGui::BeginTooltip();
  ImGui::TextColored(text, "%s", line);
  ImGui::EndTooltip();
}

// Whether the last commit that applied a value applied a typed one (lastCommitWasTyped).
bool gLastCommitTyped = false;

template <class T>
bool commit(bool changed, T* value, const std::string& lengthUnit = "") {
  gLastCommitTyped = false;
  const ImGuiID id = ImGui::GetItemID();
  if (id != 0 && ImGui::TempInputIsActive(id)) {
    // Typing starts (it did not type on the last frame): no letters of an earlier typing count.
    if (gTyped.id != id || gTyped.frame != ImGui::GetFrameCount() - 1) {
      if (gDropped.id == id) gDropped = {};
      if (gTyped.id != id) gTyped = {id, double(*value), 0, false, ""};
      // A new typing: nothing held from an earlier one, and the text it opens with is no edit
      // (a field opened and left untyped set every selected part to the primary's value).
      gTyped.held = false;
      gTyped.text = typedText(id);
    }
    // Dear ImGui applies the text to the value on the frames it is edited, and says `changed`
    // only where the value then differs from the caller's, which the caller reads afresh each
    // frame from the document: typing "15" over 15 passed through 1 (changed) and back to 15
    // (unchanged), and leaving the field applied the 1 held (an artist's test). The value after
    // every edit of the text is the one held.
    const std::string text = typedText(id);
    // Text replaced or cut short (Ctrl+A and a new number): a space between numbers typed before
    // is gone with it.
    if (text.size() < gTyped.text.size() && gDropped.id == id)
      gDropped.twoNumbers = gDropped.spaceAfterNumber = false;
    if (changed || text != gTyped.text) gTyped.value = double(*value), gTyped.held = true;
    gTyped.text = text;
    // A deleted character may have been the number's or the unit's: the unit typed is what
    // follows the last deletion (the letters never reach the field's text).
    if (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Backspace)) ||
        ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Delete)))
      if (gDropped.id == id) {
        gDropped.letters.clear();
        gDropped.twoNumbers = gDropped.spaceAfterNumber = false;
      }
    // Letters typed after a number equal to the value ("1cm" into 1 mm): due as a change, to be
    // converted when the field is left.
    if (!gTyped.held && gDropped.id == id && !gDropped.letters.empty())
      gTyped.value = double(*value), gTyped.held = true;
    gTyped.frame = ImGui::GetFrameCount();
    // Marked as being typed into: its frame in the theme's accent (a drag field opened for
    // typing looked as it did for dragging, and an artist could not tell that it waited for
    // Enter).
    ImGui::GetWindowDrawList()->AddRect(ImGui::GetItemRectMin(), ImGui::GetItemRectMax(),
                                        ImGui::GetColorU32(ImGuiCol_CheckMark),
                                        ImGui::GetStyle().FrameRounding, 0, 2.0f);
    if constexpr (std::is_floating_point_v<T>) showDroppedLetters(id, lengthUnit);
    if (typedIsExpression(text)) {  // what leaving the field will make of it
      char line[160];
      if (const std::optional<double> result = evaluateTypedExpression(text))
        std::snprintf(line, sizeof(line), "%s = %.10g when the field is left", text.c_str(),
                      *result);
      else
        std::snprintf(line, sizeof(line), "\"%s\" is no number yet", text.c_str());
      if (gDropped.id != id || gDropped.letters.empty()) hintBelowField(line);
    }
    if (gDropped.id == id && gDropped.twoNumbers)
      hintBelowField("a space between two numbers: leaving the field changes nothing");
    return false;
  }
  if (!gTyped.held || gTyped.id != id) return changed;
  // The field was left on this frame (it typed on the last): the typed value, unless Escape took
  // it back. A value held by a field that was not drawn since (its node deselected) is dropped.
  gTyped.held = false;
  if (gTyped.frame != ImGui::GetFrameCount() - 1) return changed;
  if (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape), false)) return false;
  if (!changed) *value = T(gTyped.value);
  // Two numbers apart ("15 5": the field dropped the space and read 155) or an expression that
  // is no number ("5*/2"): the field keeps its value, and says why (they were applied silently:
  // an artist's test).
  if (gDropped.id == id && gDropped.twoNumbers) {
    gRefusal = "a space between two numbers (\"" + gTyped.text.substr(0, 40) +
               "\" without it): the value is kept";
    gDropped = {};
    return false;
  }
  // An expression ("30+5", "40/2", "2*10"): its result. Dear ImGui reads the first number only
  // (30, 40, 2) and applied it without a word (an artist's test).
  if (typedIsExpression(gTyped.text)) {
    const std::optional<double> result = evaluateTypedExpression(gTyped.text);
    const bool whole = std::is_integral_v<T>;
    if (!result || (whole && (*result != std::round(*result) || std::fabs(*result) > 2e9))) {
      gRefusal = "\"" + gTyped.text.substr(0, 40) + "\" is no " +
                 (whole ? "whole number" : "number") + ": the value is kept";
      if (gDropped.id == id) gDropped = {};
      return false;
    }
    *value = T(*result);
    char said[160];
    std::snprintf(said, sizeof(said), "%s = %.10g", gTyped.text.substr(0, 40).c_str(), *result);
    gConversion = said;
  }
  // Letters that make no sense of the number: the field keeps its value (a count or a resolution
  // as much as a length).
  const std::optional<double> converted = convertTypedUnit(id, double(*value), lengthUnit);
  if (!converted) return false;
  if constexpr (std::is_floating_point_v<T>) *value = T(*converted);
  gLastCommitTyped = true;
  return true;
}

}  // namespace

bool lastCommitWasTyped() {
  return gLastCommitTyped;
}

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

// The text fields of InputInt / InputDouble widgets announced by numberFieldNext (Dear ImGui
// 1.86 keeps no trace of a text field's filter that could tell them from a name field). UI
// thread only; a handful of ids.
std::vector<ImGuiID> gNumberFields;

unsigned numberFieldBeingTyped() {
  const ImGuiContext* g = ImGui::GetCurrentContext();
  if (!g || g->ActiveId == 0) return 0;
  // A drag or slider opened for typing (its temporary input), or a number field of its own.
  const bool number =
      g->TempInputId == g->ActiveId ||
      std::find(gNumberFields.begin(), gNumberFields.end(), g->ActiveId) != gNumberFields.end();
  return number ? g->ActiveId : 0;
}

void numberFieldNext(const char* label) {
  // InputScalar draws its text field as InputText("") inside PushID(label): that field's id.
  // Without keeping it alive (GetID does in Dear ImGui 1.86): an InputInt with step buttons then
  // no longer saw its text field as the group's active item and asserted on the first character
  // typed (the export dialog's resolution ended the editor).
  ImGui::PushID(label);
  const ImGuiID id = ImGui::GetCurrentWindow()->GetIDNoKeepAlive("");
  ImGui::PopID();
  if (std::find(gNumberFields.begin(), gNumberFields.end(), id) == gNumberFields.end())
    gNumberFields.push_back(id);
}

bool typingIntoNumberField() {
  return numberFieldBeingTyped() != 0;
}

unsigned numberFieldCharacter(unsigned codepoint, std::string* dropped) {
  if (!typingIntoNumberField()) return codepoint;
  if (codepoint == ',') codepoint = '.';
  const bool kept = (codepoint >= '0' && codepoint <= '9') || codepoint == '.' ||
                    codepoint == '+' || codepoint == '-' || codepoint == '*' || codepoint == '/' ||
                    codepoint == 'e' || codepoint == 'E';
  const ImGuiID field = numberFieldBeingTyped();
  // The letters of this typing only (the field's typing began when it became active): those of
  // an earlier typing into it, never committed (a field that converts nothing), are forgotten.
  const ImGuiContext* g = ImGui::GetCurrentContext();
  const double since = g->Time - double(g->ActiveIdTimer);
  if (gDropped.id != field || std::fabs(gDropped.since - since) > 1e-6)
    gDropped = {field, "", since, false};
  if (kept || codepoint == ' ') {
    // A number typed after the letters ("1 cm 2" became 12 cm): the letters are no unit of it.
    if (!gDropped.letters.empty() && codepoint != ' ') gDropped.numberAfter = true;
    // A number typed after a space after a number ("15 5": the field drops the space).
    const bool digit = (codepoint >= '0' && codepoint <= '9') || codepoint == '.';
    if (codepoint == ' ') {
      const std::string text = typedText(field);
      const char last = text.empty() ? '\0' : text.back();
      if ((last >= '0' && last <= '9') || last == '.') gDropped.spaceAfterNumber = true;
    } else if (digit && gDropped.spaceAfterNumber && gDropped.letters.empty()) {
      gDropped.twoNumbers = true;
    } else if (!digit) {
      gDropped.spaceAfterNumber = false;  // "5 *2", "5 e": no second number
    }
    return codepoint;
  }
  gDropped.spaceAfterNumber = false;  // a unit after the space
  // Kept for the field's commit, which converts a length unit (commitTypedValue).
  const size_t before = dropped->size();
  // As UTF-8, so that a micro sign or a degree sign is said too.
  if (codepoint < 0x80) {
    dropped->push_back(char(codepoint));
  } else if (codepoint < 0x800) {
    dropped->push_back(char(0xC0 | (codepoint >> 6)));
    dropped->push_back(char(0x80 | (codepoint & 0x3F)));
  } else if (codepoint < 0x10000) {
    dropped->push_back(char(0xE0 | (codepoint >> 12)));
    dropped->push_back(char(0x80 | ((codepoint >> 6) & 0x3F)));
    dropped->push_back(char(0x80 | (codepoint & 0x3F)));
  }
  gDropped.letters += dropped->substr(before);
  return codepoint;
}

bool commitTypedValue(bool changed, double* value, const std::string& lengthUnit) {
  return commit(changed, value, lengthUnit);
}

TypedUnit convertLengthTypedIntoInput(double* value, const std::string& lengthUnit) {
  const ImGuiID id = ImGui::GetItemID();
  if (id == 0 || gDropped.id != id) return TypedUnit::None;
  if (ImGui::IsItemActive()) {
    if (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Backspace)) ||
        ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Delete)))
      gDropped.letters.clear();
    showDroppedLetters(id, lengthUnit);
    return TypedUnit::None;
  }
  if (!ImGui::IsItemDeactivated() ||
      ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape), false)) {
    gDropped = {};  // left by Escape (or long ago): nothing to convert
    return TypedUnit::None;
  }
  const double before = *value;
  const std::optional<double> converted = convertTypedUnit(id, *value, lengthUnit);
  if (!converted) return TypedUnit::Refused;
  *value = *converted;
  return !gConversion.empty() && *value != before ? TypedUnit::Converted : TypedUnit::None;
}

bool typedIsExpression(const std::string& text) {
  for (size_t i = 1; i < text.size(); ++i) {
    const char c = text[i], before = text[i - 1];
    if ((c == '+' || c == '-' || c == '*' || c == '/') &&
        ((before >= '0' && before <= '9') || before == '.'))
      return true;
  }
  return false;
}

std::optional<double> evaluateTypedExpression(const std::string& text) {
  size_t at = 0;
  const auto skip = [&] {
    while (at < text.size() && text[at] == ' ') ++at;
  };
  // A number, or a sign before one.
  // Only what a number field keeps (strtod alone would also read "0x10" and "inf").
  for (char c : text)
    if (!((c >= '0' && c <= '9') || c == '.' || c == 'e' || c == 'E' || c == '+' || c == '-' ||
          c == '*' || c == '/' || c == ' '))
      return std::nullopt;
  // Signs counted in a loop, not by recursion (any text, however many signs, stays bounded).
  const auto factor = [&]() -> std::optional<double> {
    bool minus = false;
    for (skip(); at < text.size() && (text[at] == '+' || text[at] == '-'); skip())
      minus = minus != (text[at++] == '-');
    if (at >= text.size() || !((text[at] >= '0' && text[at] <= '9') || text[at] == '.'))
      return std::nullopt;
    char* end = nullptr;
    const double magnitude = std::strtod(text.c_str() + at, &end);
    if (end == text.c_str() + at) return std::nullopt;
    const double v = minus ? -magnitude : magnitude;
    at = size_t(end - text.c_str());
    return v;
  };
  const auto product = [&]() -> std::optional<double> {
    std::optional<double> v = factor();
    while (v) {
      skip();
      if (at >= text.size() || (text[at] != '*' && text[at] != '/')) break;
      const bool times = text[at++] == '*';
      const std::optional<double> w = factor();
      if (!w) return std::nullopt;
      v = times ? *v * *w : *v / *w;
    }
    return v;
  };
  std::optional<double> v = product();
  while (v) {
    skip();
    if (at >= text.size() || (text[at] != '+' && text[at] != '-')) break;
    const bool plus = text[at++] == '+';
    const std::optional<double> w = product();
    if (!w) return std::nullopt;
    v = plus ? *v + *w : *v - *w;
  }
  skip();
  if (!v || at != text.size() || !std::isfinite(*v)) return std::nullopt;
  return v;
}

std::string takeTypedRefusal() {
  std::string said;
  said.swap(gRefusal);
  return said;
}

std::string droppedLettersHint() {
  std::string shown;
  shown.swap(gHintShown);
  return shown;
}

bool takeUnitConverted() {
  const bool converted = gConverted;
  gConverted = false;
  return converted;
}

std::string takeUnitConversion() {
  std::string said;
  said.swap(gConversion);
  return said;
}
bool commitTypedValue(bool changed, int* value) {
  return commit(changed, value);
}

AmountDrag amountDrag(double amount, bool signedAmount, double dragSign, double floorSpeed) {
  AmountDrag d;
  d.speed = std::max(std::fabs(amount) * 0.01, floorSpeed);
  d.lo = signedAmount ? -1e300 : 1e-6;
  d.hi = 1e300;
  if (signedAmount && dragSign > 0.0) d.lo = 0.0;
  if (signedAmount && dragSign < 0.0) d.hi = 0.0;
  return d;
}

namespace {
ImGuiID gDragItem = 0;    // the field a drag pressed last
double gDragStart = 0.0;  // its value at the press
}  // namespace

bool dragFromItsStart(bool changed, double before, double* value, double speed,
                      const double* minimum) {
  const ImGuiID id = ImGui::GetItemID();
  if (ImGui::IsItemActivated()) {
    gDragItem = id;
    gDragStart = before;
  }
  if (!changed || gDragItem != id || !ImGui::IsItemActive() || !ImGui::IsMouseDown(0) ||
      ImGui::TempInputIsActive(id))
    return changed;
  const ImGuiIO& io = ImGui::GetIO();
  double step = speed;
  if (io.KeyAlt) step *= 0.01;
  if (io.KeyShift) step *= 10.0;
  if (!(step > 0.0) || !std::isfinite(step)) return changed;
  double v = gDragStart + double(ImGui::GetMouseDragDelta(0, 0.0f).x) * step;
  // A tenth of the step's leading digit, written back as it reads (0.1 + 0.2 is 0.3).
  const double grain = std::pow(10.0, std::floor(std::log10(step)) - 1.0);
  v = std::round(v / grain) * grain;
  char text[40];
  std::snprintf(text, sizeof(text), "%.12g", v);
  v = std::strtod(text, nullptr);
  if (minimum && v < *minimum) v = *minimum;
  *value = v;
  return true;
}

}  // namespace strata::ui
