// A number typed into a drag or slider field is applied once, when it is complete, not per
// keystroke. Dear ImGui 1.86 writes a field's text input (double-click or Ctrl+click) into the
// value at every character, so "25" passed through 2 (a part moved, the preview evaluated at a
// resolution of 16 on the way to 512, an undo step that held the wrong value). Call right after
// the widget, on the UI thread, with what it returned and the variable it edits.
#pragma once

#include <optional>
#include <string>

namespace strata::ui {

// Returns whether the caller should apply `*value` now. While the last item's text input is
// active, false, and the typed value is held (at most one field types at a time); the field's
// frame is then drawn in the theme's accent: it is being typed into. On the frame
// the field is left (Enter, Tab, a click elsewhere), true with `*value` the typed value; Escape
// drops it (false, as Dear ImGui restores the text). A drag with the mouse: `changed` as given.
// `lengthUnit` (a length field's unit, "mm" or "millimetre"; "" for other fields): a length unit
// typed after the number ("1cm", "0.5 in", "2 m"; import_options.h: sceneUnitMetres) converts
// the typed value into the field's unit ("1cm" in a mm field: 10; it was dropped and gave 1),
// said by takeUnitConversion. Letters that make no sense of the number (no unit, a length in a
// field that is no length, letters before a number: "1 cm 2") apply nothing: false, the field
// keeps its value. Degrees typed into a field that is no length are taken as the number.
bool commitTypedValue(bool changed, double* value, const std::string& lengthUnit = "");
bool commitTypedValue(bool changed, int* value);
// A mouse drag of a number field (DragScalar) made absolute: the value at the press plus the
// mouse's travel since then times `speed` (ten times with Shift, a hundredth with Alt, as Dear
// ImGui), kept at or above `*minimum` where given, rounded to a tenth of `speed` (times those
// factors). Dear ImGui adds each frame's motion to the value it clamped and rounded the frame
// before, so a drag out past the minimum and back did not come back (a plate's thickness went
// 8 -> 0.000001 -> 33.6 mm, and a drag of 20 pixels out and back 8 -> 2.96 -> 8.56: an artist's
// test). Call right after the DragScalar, before commitTypedValue, with `before` the value it
// was given; returns `changed`. A typed number (the mouse up) is left as it is. UI thread.
bool dragFromItsStart(bool changed, double before, double* value, double speed,
                      const double* minimum = nullptr);
// Whether the last commitTypedValue call applied a number typed into the field (true) rather
// than a drag's value or nothing (false): a field shared by several parts sets every one to a
// typed number, where a drag moves each by as much. UI thread.
bool lastCommitWasTyped();
// For a length typed into an InputDouble field (announced by numberFieldNext), which applies
// its number at every keystroke: call right after it. On the frame the field is left, a length
// unit typed after the number converts `*value` into `lengthUnit` (the scene's unit: "1cm" in a
// mm field gives 10), said by takeUnitConversion: Converted. Letters that are no unit of the
// number: Refused, and the caller puts the value back as it was before the typing. A deletion
// drops the unit typed before it; Escape (the field restores its value) converts nothing.
enum class TypedUnit { None, Converted, Refused };
TypedUnit convertLengthTypedIntoInput(double* value, const std::string& lengthUnit);
// What the last commit converted ("1 cm is 10 mm"), once; "" for none. The editor says it in place
// of "a unit typed is not converted" (the letters it was told of by numberFieldCharacter).
std::string takeUnitConversion();
// While a number field is typed, its dropped letters are drawn dimmed after its text (the field
// itself never shows them) with a line under it saying what leaving the field will make of them
// ("1.5 cm: 15 mm when the field is left"; "\"xyz\" is no unit: the number is kept"): by
// commitTypedValue and convertLengthTypedIntoInput. The last such line drawn, once ("" for none).
std::string droppedLettersHint();
// An expression typed into a number field ("30+5", "40/2", "2*10", "-5*-2"): a binary + - * /
// after a digit or a point (a leading sign, or an exponent's "1e-3", is none; "*2" alone is Dear
// ImGui's own "times the value"). Dear ImGui reads only the first number of it (30, 40, 2) and
// applied that without a word (an artist's test): the commit applies the expression's result
// instead (said by takeUnitConversion: "30+5 = 35"), and refuses one that is no number ("5*/2")
// or two numbers apart ("15 5", which the field shows as 155), keeping the value (said by
// takeTypedRefusal). While typing, a line under the field says what leaving it will do.
bool typedIsExpression(const std::string& text);
// The value of `text`: numbers (strtod's, exponents too) joined by + - * / with the usual
// precedence, signs before numbers (any number of them), spaces between; none where it is
// malformed, holds another character ("0x10") or is not finite (a division by zero).
std::optional<double> evaluateTypedExpression(const std::string& text);
// What the last commit refused and why ("a space between two numbers ...: the value is kept"),
// once; "" for none. The inspector says it as a warning.
std::string takeTypedRefusal();
// Whether a commit converted a length unit since the last call (whoever took its text): the
// letters the field dropped were that unit.
bool takeUnitConverted();

// A double-click on a slider opens its text field, as it does on a drag field (Dear ImGui 1.86's
// sliders take only Ctrl+click). Call right after the slider with its value before the call.
// On the double-click's frame returns true with `*beforePress` the value the double-click's
// first press jumped from (a slider's press sets the value under the pointer), which the caller
// puts back, so that the field opens at it and Escape keeps it.
bool doubleClickOpensTyping(double before, double* beforePress);

// A character typed while a number field's text is being edited (a drag or slider field opened
// for typing: Dear ImGui's temporary input, which keeps digits, signs, '.', 'e', '*' and '/' and
// drops the rest without a word): a decimal comma becomes the decimal point (it was dropped, so
// "9,5" became 95), and what the field will drop is added to *dropped (letters of a unit: "5 mm"
// became 5, "0.5 in" 0.5 mm), for the editor to say; a number typed after such letters makes
// them no unit ("1 cm 2" is the 12 the field shows, not 12 cm). Letters count for the typing they
// were typed in. Other fields' characters pass as typed.
// Call with the current ImGui context, before the character reaches it.
unsigned numberFieldCharacter(unsigned codepoint, std::string* dropped);
// Whether a number field's text is being edited now: a drag or slider opened for typing, or an
// InputInt / InputDouble field; numberFieldBeingTyped gives its ImGui id (0: none).
bool typingIntoNumberField();
unsigned numberFieldBeingTyped();
// Call right before an ImGui::InputInt / InputDouble (same ID stack) with its label: its text
// field is then a number field for numberFieldCharacter.
void numberFieldNext(const char* label);

// How a modifier's amount field (distance, thickness, radius) drags: `speed` units a pixel, the
// value held within [lo, hi]. A percent of the amount a pixel, at least `floorSpeed` (the
// scene's speed took a 2 mm offset to +10 mm in 60 pixels, through zero, and a round of 0.8 mm
// to 8.4 in 40: an artist's test). A signed amount (an offset) dragged from one side of zero
// (`dragSign`: the amount's sign where the running drag began, 0 when not dragging) stops at
// zero rather than turning a shrink into a growth; a typed value may cross it. Unsigned amounts
// stay above 1e-6.
struct AmountDrag {
  double speed = 0.0, lo = 0.0, hi = 0.0;
};
AmountDrag amountDrag(double amount, bool signedAmount, double dragSign, double floorSpeed);

}  // namespace strata::ui
