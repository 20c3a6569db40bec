// A number typed into a drag or slider field is applied once, when the field is left
// (ui/typed_value.h), never per keystroke; a double-click opens a slider's text field. Drives Dear
// ImGui without a window: frames with characters and keys fed to its IO, as the editor's GLFW
// backend feeds them.
#include <gtest/gtest.h>

#include <imgui.h>
#include <functional>

#include <string>
#include <vector>

#include "ui/typed_value.h"

namespace strata::ui {
namespace {

constexpr int kEnter = 1, kEscape = 2, kTab = 3, kBackspace = 4;

// A Dear ImGui context without a window, as the editor's backend sets one up: its display, the
// keys the tests press, a font atlas built.
void startImGui() {
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(800, 600);
  io.DeltaTime = 1.0f / 60.0f;
  io.IniFilename = nullptr;
  io.KeyMap[ImGuiKey_Enter] = kEnter;
  io.KeyMap[ImGuiKey_Escape] = kEscape;
  io.KeyMap[ImGuiKey_Tab] = kTab;
  io.KeyMap[ImGuiKey_Backspace] = kBackspace;
  unsigned char* pixels = nullptr;
  int w = 0, h = 0;
  io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
}

// A field whose value comes from `stored` each frame, as the inspector's come from the
// document, and writes back to it (recording each write) when commitTypedValue says so.
class TypedField : public ::testing::Test {
 protected:
  void SetUp() override {
    startImGui();
    frame();  // lays the window out
  }
  void TearDown() override { ImGui::DestroyContext(); }

  // One frame; `focus` opens the field's text input (as a double-click does).
  void frame(bool focus = false) {
    ImGui::NewFrame();
    ImGui::SetNextWindowPos(ImVec2(0, 0));
    ImGui::SetNextWindowSize(ImVec2(300, 200));
    ImGui::Begin("fields");
    if (focus) ImGui::SetKeyboardFocusHere();
    double value = stored;
    // The field of the part selected (none once the tree's row was clicked).
    const double before = value;
    if (!rowClicked &&
        commitTypedValue(
            absoluteDrag ? dragFromItsStart(ImGui::DragScalar("##v", ImGuiDataType_Double, &value,
                                                              1.0f, dragMinimum, nullptr),
                                            before, &value, 1.0, dragMinimum)
                         : ImGui::DragScalar("##v", ImGuiDataType_Double, &value, 1.0f, dragMinimum,
                                             nullptr),
            &value, lengthUnit))
      stored = value, writes.push_back(value), typedWrites.push_back(lastCommitWasTyped());
    // A second field after it, which Tab moves to.
    double other = storedOther;
    if (commitTypedValue(ImGui::DragScalar("##w", ImGuiDataType_Double, &other, 1.0f), &other))
      storedOther = other, otherWrites.push_back(other);
    // A slider whose double-click opens its text field (as the Preview panel's resolution).
    double slid = storedSlider;
    const double sliderBefore = slid;
    const double lo = 0.0, hi = 100.0;
    if (commitTypedValue(ImGui::SliderScalar("##s", ImGuiDataType_Double, &slid, &lo, &hi), &slid))
      storedSlider = slid;
    sliderMin = ImGui::GetItemRectMin();
    double beforePress = 0.0;
    if (doubleClickOpensTyping(sliderBefore, &beforePress)) storedSlider = beforePress;
    ImGui::End();
    // A tree after the fields, as the editor draws its outliner after the inspector: a click on
    // its row selects another part, whose fields are not the ones typed into.
    ImGui::SetNextWindowPos(ImVec2(400, 0));
    ImGui::SetNextWindowSize(ImVec2(200, 100));
    ImGui::Begin("tree");
    ImGui::Selectable("another part", rowClicked);
    if (ImGui::IsItemClicked(0)) rowClicked = true;  // on the press, as the outliner selects
    ImGui::End();
    ImGui::Render();
  }
  void type(const char* text) {
    for (const char* c = text; *c; ++c) {
      ImGui::GetIO().AddInputCharacter(static_cast<unsigned>(*c));
      frame();
    }
  }
  void press(int key) {
    ImGui::GetIO().KeysDown[key] = true;
    frame();
    ImGui::GetIO().KeysDown[key] = false;
    frame();
  }

  bool rowClicked = false;
  bool absoluteDrag = false;            // the first field's drag through dragFromItsStart
  const double* dragMinimum = nullptr;  // the first field's drag minimum
  std::string lengthUnit;               // the first field's, when it is a length ("" otherwise)
  double storedSlider = 50.0;
  ImVec2 sliderMin{};
  double stored = 7.0, storedOther = 1.0;
  std::vector<double> writes, otherWrites;
  std::vector<bool> typedWrites;  // lastCommitWasTyped() at each of the first field's writes
};

TEST_F(TypedField, ANumberIsAppliedOnceWhenEnterIsPressed) {
  frame(/*focus=*/true);
  frame();
  type("25");
  EXPECT_TRUE(writes.empty()) << "applied while typing: " << writes.front();
  EXPECT_EQ(stored, 7.0);
  press(kEnter);
  ASSERT_EQ(writes.size(), 1u);
  EXPECT_EQ(stored, 25.0);
  EXPECT_TRUE(typedWrites.back()) << "a typed number: a field shared by several parts sets all";
  frame();
  EXPECT_EQ(writes.size(), 1u);
  // A drag with the mouse: not typed (each part moves by as much).
  ImGuiIO& io = ImGui::GetIO();
  io.MousePos = ImVec2(40, 30);
  frame();
  io.MouseDown[0] = true;
  frame();
  for (int k = 0; k < 4; ++k) {
    io.MousePos.x += 10;
    frame();
  }
  io.MouseDown[0] = false;
  frame();
  ASSERT_GT(writes.size(), 1u) << "the drag wrote";
  EXPECT_FALSE(typedWrites.back());
  EXPECT_FALSE(lastCommitWasTyped());
}

// A drag out past the field's minimum and back to where it was pressed gives the value it had:
// Dear ImGui adds each frame's motion to the value it clamped, so it did not come back (a
// plate's thickness 8 -> 0.000001 -> 33.6 mm: an artist's test). Plain Dear ImGui beside it.
TEST_F(TypedField, ADragOutPastTheMinimumAndBackGivesTheValueItHad) {
  const double zero = 0.0;
  dragMinimum = &zero;
  ImGuiIO& io = ImGui::GetIO();
  const auto dragOutAndBack = [&] {
    stored = 7.0;
    io.MousePos = ImVec2(40, 30);
    frame();
    io.MouseDown[0] = true;
    frame();
    double lowest = stored;
    for (int k = 0; k < 12; ++k) {  // 120 pixels left: past 0 at 1 a pixel
      io.MousePos.x -= 10;
      frame();
      lowest = std::min(lowest, stored);
    }
    EXPECT_EQ(lowest, 0.0) << "kept at the minimum";
    for (int k = 0; k < 12; ++k) {
      io.MousePos.x += 10;
      frame();
    }
    io.MouseDown[0] = false;
    frame();
    return stored;
  };
  absoluteDrag = true;
  EXPECT_EQ(dragOutAndBack(), 7.0);
  EXPECT_FALSE(lastCommitWasTyped());
  absoluteDrag = false;
  EXPECT_GT(dragOutAndBack(), 7.0) << "plain Dear ImGui came back: the test shows nothing";
}

// Typing the number a field already holds keeps it: "15" over 15 passed through 1 (a change) and
// back to 15 (no change to the value the field reads afresh each frame), and leaving the field
// applied the 1 (an artist's test: a hub retyped "to be sure" sank into its plate).
TEST_F(TypedField, TypingTheNumberTheFieldHoldsKeepsIt) {
  for (const char* same : {"15", "15.0", "150"}) {
    SCOPED_TRACE(same);
    stored = 15.0;
    writes.clear();
    frame(/*focus=*/true);
    frame();
    type(same);
    press(kEnter);
    EXPECT_EQ(stored, std::string(same) == "150" ? 150.0 : 15.0);
    for (double w : writes) EXPECT_NE(w, 1.0) << "the first digit was applied";
    frame();
  }
  // Opened and left untyped, after a typing into the same field and a fresh one alike: nothing
  // is applied (a field shared by several parts would set them all to the primary's value).
  for (int round = 0; round < 2; ++round) {
    const size_t before = writes.size();
    frame(/*focus=*/true);
    frame();
    frame();
    press(kEnter);
    EXPECT_EQ(writes.size(), before) << "round " << round;
    frame();
  }
}

// An artist typed "9,5" and got 95: Dear ImGui's number fields drop the comma. Typed through
// numberFieldCharacter (as the editor feeds characters), the comma is the decimal point, and a
// unit's letters, which the field drops, are reported instead of vanishing; a name field (no
// number field typing) gets every character as typed.
TEST_F(TypedField, ADecimalCommaIsThePointAndDroppedLettersAreReported) {
  lengthUnit = "mm";  // "mm" after the number: its own unit
  std::string dropped;
  EXPECT_FALSE(typingIntoNumberField());
  EXPECT_EQ(numberFieldCharacter(',', &dropped), unsigned(','));
  EXPECT_EQ(numberFieldCharacter('m', &dropped), unsigned('m'));
  EXPECT_TRUE(dropped.empty());
  frame(/*focus=*/true);
  frame();
  EXPECT_TRUE(typingIntoNumberField());
  for (const char* c = "9,5 mm"; *c; ++c) {
    ImGui::GetIO().AddInputCharacter(numberFieldCharacter(static_cast<unsigned>(*c), &dropped));
    frame();
  }
  press(kEnter);
  ASSERT_EQ(writes.size(), 1u);
  EXPECT_EQ(stored, 9.5);
  EXPECT_EQ(dropped, "mm");
  EXPECT_FALSE(typingIntoNumberField());
}

// An artist typed "1cm" into a radius in a millimetre scene and got 1 mm (the field drops the
// letters): a length unit typed after the number converts it into the field's unit, and says
// so; letters that name no unit are only reported; a field that is no length keeps the number.
TEST_F(TypedField, ALengthTypedWithAUnitIsConverted) {
  lengthUnit = "mm";
  const auto typeInto = [&](const char* text, std::string* dropped) {
    frame(/*focus=*/true);
    frame();
    for (const char* c = text; *c; ++c) {
      ImGui::GetIO().AddInputCharacter(numberFieldCharacter(static_cast<unsigned>(*c), dropped));
      frame();
    }
    press(kEnter);
  };
  std::string dropped;
  typeInto("1,5cm", &dropped);
  EXPECT_EQ(stored, 15.0);
  EXPECT_EQ(takeUnitConversion(), "1.5 cm is 15 mm");
  EXPECT_EQ(takeUnitConversion(), "");
  dropped.clear();
  typeInto("2 in", &dropped);
  EXPECT_NEAR(stored, 50.8, 1e-12);
  // Letters that are no unit: nothing applied, the field keeps its value ("3 xyz" gave 3 mm).
  typeInto("3 xyz", &dropped);
  EXPECT_NEAR(stored, 50.8, 1e-12);
  takeUnitConversion();
  EXPECT_EQ(takeUnitConversion(), "");
  // The number already in the field: converted all the same (1 mm and "1cm" typed: 10 mm).
  stored = 1.0;
  typeInto("1cm", &dropped);
  EXPECT_EQ(stored, 10.0);
  EXPECT_EQ(takeUnitConversion(), "1 cm is 10 mm");
  // A unit typed, then the number deleted and typed again: the deletion took the unit along.
  frame(/*focus=*/true);
  frame();
  for (const char* c = "3in"; *c; ++c) {
    ImGui::GetIO().AddInputCharacter(numberFieldCharacter(static_cast<unsigned>(*c), &dropped));
    frame();
  }
  press(kBackspace);
  ImGui::GetIO().AddInputCharacter(numberFieldCharacter('3', &dropped));
  frame();
  press(kEnter);
  EXPECT_EQ(stored, 3.0);
  EXPECT_EQ(takeUnitConversion(), "");
  // A number typed after the unit ("1 cm 2" became 12 mm, the field showing "12"): the letters
  // are no unit of it; nothing applied, the letters said.
  dropped.clear();
  typeInto("1 cm 2", &dropped);
  EXPECT_EQ(stored, 3.0);
  EXPECT_EQ(takeUnitConversion(), "");
  EXPECT_EQ(dropped, "cm");
  lengthUnit.clear();  // an angle, a count: a length unit makes no sense there, degrees do
  typeInto("4 cm", &dropped);
  EXPECT_EQ(stored, 3.0);
  EXPECT_EQ(takeUnitConversion(), "");
  takeUnitConverted();
  frame(/*focus=*/true);
  frame();
  for (unsigned c : {unsigned('3'), unsigned('0'), 0x00B0u}) {  // "30°"
    ImGui::GetIO().AddInputCharacter(numberFieldCharacter(c, &dropped));
    frame();
  }
  press(kEnter);
  EXPECT_EQ(stored, 30.0);
  EXPECT_TRUE(takeUnitConverted()) << "its letters understood: not said as letters not typed";
}

// An artist typed "30+5" and got 30, "2*10" and got 2, "15 5" and got 155, without a word: an
// expression gives its result (and says it), one that is no number or two numbers apart keep the
// value (and say why); a leading sign, an exponent, a unit after an expression work as before.
TEST_F(TypedField, AnExpressionGivesItsResultAndTwoNumbersApartAreRefused) {
  lengthUnit = "mm";
  std::string dropped;
  const auto typeInto = [&](const char* text) {
    frame(/*focus=*/true);
    frame();
    for (const char* c = text; *c; ++c) {
      ImGui::GetIO().AddInputCharacter(numberFieldCharacter(static_cast<unsigned>(*c), &dropped));
      frame();
    }
    press(kEnter);
  };
  typeInto("30+5");
  EXPECT_EQ(stored, 35.0);
  EXPECT_EQ(takeUnitConversion(), "30+5 = 35");
  typeInto("40/2");
  EXPECT_EQ(stored, 20.0);
  typeInto("2*10-4/8");
  EXPECT_EQ(stored, 19.5);
  typeInto("-5*-2");
  EXPECT_EQ(stored, 10.0);
  typeInto("1e-3");
  EXPECT_EQ(stored, 0.001);
  takeUnitConversion();
  typeInto("1+1cm");  // the result in the unit typed
  EXPECT_EQ(stored, 20.0);
  takeUnitConversion();
  EXPECT_EQ(takeTypedRefusal(), "");
  stored = 7.0;
  typeInto("15 5");
  EXPECT_EQ(stored, 7.0);
  EXPECT_NE(takeTypedRefusal().find("a space between two numbers"), std::string::npos);
  typeInto("5*/2");
  EXPECT_EQ(stored, 7.0);
  EXPECT_EQ(takeTypedRefusal(), "\"5*/2\" is no number: the value is kept");
  typeInto("5/0");
  EXPECT_EQ(stored, 7.0);
  EXPECT_NE(takeTypedRefusal(), "");
  // Two numbers apart, then all of it replaced (Ctrl+A) by one number: that number.
  frame(/*focus=*/true);
  frame();
  for (const char* c = "15 5"; *c; ++c) {
    ImGui::GetIO().AddInputCharacter(numberFieldCharacter(static_cast<unsigned>(*c), &dropped));
    frame();
  }
  press(kBackspace);
  press(kBackspace);
  ImGui::GetIO().AddInputCharacter(numberFieldCharacter('2', &dropped));
  frame();
  press(kEnter);
  EXPECT_EQ(stored, 12.0);
  EXPECT_EQ(takeTypedRefusal(), "");
  typeInto("5 mm");  // a space before a unit is no second number
  EXPECT_EQ(stored, 5.0);
  EXPECT_EQ(takeTypedRefusal(), "");
  takeUnitConversion();
}

TEST(TypedExpression, NumbersJoinedByTheFourOperations) {
  EXPECT_FALSE(typedIsExpression("-5"));
  EXPECT_FALSE(typedIsExpression("1e-3"));
  EXPECT_FALSE(typedIsExpression("*2"));  // Dear ImGui's own: times the value
  EXPECT_TRUE(typedIsExpression("5-3"));
  EXPECT_TRUE(typedIsExpression("2.*3"));
  EXPECT_EQ(evaluateTypedExpression("1+2*3"), 7.0);
  EXPECT_EQ(evaluateTypedExpression("8/4/2"), 1.0);
  EXPECT_EQ(evaluateTypedExpression("10-2-3"), 5.0);
  EXPECT_EQ(evaluateTypedExpression("-2*-3"), 6.0);
  EXPECT_EQ(evaluateTypedExpression(" 1.5e2 + 1 "), 151.0);
  EXPECT_FALSE(evaluateTypedExpression("1+"));
  EXPECT_FALSE(evaluateTypedExpression("1**2"));
  EXPECT_FALSE(evaluateTypedExpression("1/0"));
  EXPECT_FALSE(evaluateTypedExpression(""));
  // Hostile text: a hundred thousand signs are counted, not recursed into; hex and words refused.
  EXPECT_EQ(evaluateTypedExpression(std::string(100000, '-') + "5"), 5.0);
  EXPECT_EQ(evaluateTypedExpression("2*" + std::string(99999, '-') + "3"), -6.0);
  EXPECT_FALSE(evaluateTypedExpression("0x10"));
  EXPECT_FALSE(evaluateTypedExpression("inf"));
  EXPECT_FALSE(evaluateTypedExpression("1e999"));
}

// The letters of a unit never reach the field's text ("1cm" showed "1" until the field was left):
// they are drawn after it while typing, with what leaving the field will make of them.
TEST_F(TypedField, TheLettersTypedAreShownWithWhatTheyWillDo) {
  lengthUnit = "mm";
  std::string dropped;
  const auto typeSome = [&](const char* text) {
    for (const char* c = text; *c; ++c) {
      ImGui::GetIO().AddInputCharacter(numberFieldCharacter(static_cast<unsigned>(*c), &dropped));
      frame();
    }
  };
  frame(/*focus=*/true);
  frame();
  droppedLettersHint();
  typeSome("1,5");
  EXPECT_EQ(droppedLettersHint(), "");  // no letters: nothing drawn
  typeSome("cm");
  EXPECT_EQ(droppedLettersHint(), "1.5 cm: 15 mm when the field is left");
  typeSome(" 2");
  EXPECT_EQ(droppedLettersHint(),
            "\"cm\" before a number is no unit: leaving the field changes nothing");
  press(kEscape);
  frame();
  EXPECT_EQ(droppedLettersHint(), "");  // left: nothing shown
  frame(/*focus=*/true);
  frame();
  typeSome("3 xyz");
  EXPECT_EQ(droppedLettersHint(),
            "\"xyz\" is no unit (mm, cm, m, in, ft): leaving the field changes nothing");
  press(kEnter);
  EXPECT_EQ(stored, 7.0);
  lengthUnit.clear();
  frame(/*focus=*/true);
  frame();
  typeSome("4 cm");
  EXPECT_EQ(droppedLettersHint(), "\"cm\": this field is no length: leaving it changes nothing");
  press(kEnter);
  EXPECT_EQ(stored, 7.0);
  takeUnitConversion();
}

// Types `text` (through numberFieldCharacter, as the editor feeds characters) into the number
// field that `widget` draws (announced by numberFieldNext), then Enter, in an ImGui context of
// its own; returns the letters the field dropped.
std::string typeIntoNumberField(const std::function<void()>& widget, const char* text) {
  startImGui();
  ImGuiIO& io = ImGui::GetIO();
  bool focus = true;
  const auto frame = [&] {
    ImGui::NewFrame();
    ImGui::Begin("w");
    if (focus) ImGui::SetKeyboardFocusHere();
    focus = false;
    widget();
    ImGui::End();
    ImGui::Render();
  };
  frame();
  frame();
  EXPECT_TRUE(typingIntoNumberField());
  std::string dropped;
  for (const char* c = text; *c; ++c) {
    io.AddInputCharacter(numberFieldCharacter(static_cast<unsigned>(*c), &dropped));
    frame();
  }
  io.KeysDown[kEnter] = true;
  frame();
  io.KeysDown[kEnter] = false;
  frame();
  ImGui::DestroyContext();
  return dropped;
}

// The same in a number field of its own (the status bar's move step is an InputDouble): the
// comma is the point there too (a review found "9,5" still became 95 in such fields).
TEST(NumberField, AnInputDoubleTakesADecimalCommaToo) {
  double value = 1.0;
  const std::string dropped = typeIntoNumberField(
      [&] {
        numberFieldNext("step");
        ImGui::InputDouble("step", &value, 0.0, 0.0, "%.4g");
      },
      "9,5");
  EXPECT_EQ(value, 9.5);
  EXPECT_TRUE(dropped.empty()) << dropped;
}

// A length typed with a unit into a number field of its own (the status bar's move step, in a
// millimetre scene): converted once the field is left ("1cm" gave 1 mm there, the letters
// dropped), and said.
TEST(NumberField, ALengthTypedWithAUnitIntoAnInputDoubleIsConverted) {
  const auto typed = [](const char* text) {
    double value = 2.0;
    double before = value;
    typeIntoNumberField(
        [&] {
          numberFieldNext("step");
          ImGui::InputDouble("step", &value, 0.0, 0.0, "%.4g");
          if (ImGui::IsItemActivated()) before = value;
          if (convertLengthTypedIntoInput(&value, "mm") == TypedUnit::Refused) value = before;
        },
        text);
    return value;
  };
  takeUnitConversion();
  droppedLettersHint();
  EXPECT_EQ(typed("1cm"), 10.0);
  EXPECT_EQ(takeUnitConversion(), "1 cm is 10 mm");
  EXPECT_EQ(droppedLettersHint(), "1 cm: 10 mm when the field is left");  // shown while typing
  EXPECT_NEAR(typed("0,5 in"), 12.7, 1e-12);
  EXPECT_EQ(takeUnitConversion(), "0.5 in is 12.7 mm");
  EXPECT_EQ(typed("3"), 3.0);  // no unit: the number as typed
  EXPECT_EQ(takeUnitConversion(), "");
  EXPECT_EQ(typed("4 xyz"), 2.0);  // no unit it knows: the value it had (the letters are said)
  EXPECT_EQ(takeUnitConversion(), "");
  EXPECT_EQ(typed("1 cm 2"), 2.0);  // letters before a number: no unit of it, the value it had
  EXPECT_EQ(takeUnitConversion(), "");
}

// An InputInt with step buttons (the export dialog's resolution) announced as a number field:
// a character typed into it ended the editor (numberFieldNext kept its text field alive, so the
// InputInt's group did not take it as its active item and Dear ImGui asserted).
TEST(NumberField, AnInputIntWithStepsTakesTyping) {
  int value = 192;
  typeIntoNumberField(
      [&] {
        numberFieldNext("cells");
        ImGui::InputInt("cells", &value, 64, 256);
      },
      "1,5");
  EXPECT_EQ(value, 1);  // an integer field: "1.5" is 1
}

TEST_F(TypedField, EscapeKeepsTheValue) {
  frame(/*focus=*/true);
  frame();
  type("3");
  press(kEscape);
  EXPECT_TRUE(writes.empty());
  EXPECT_EQ(stored, 7.0);
}

TEST_F(TypedField, TabAppliesTheNumberAndTypesIntoTheNextField) {
  frame(/*focus=*/true);
  frame();
  type("12");
  press(kTab);
  ASSERT_EQ(writes.size(), 1u);
  EXPECT_EQ(stored, 12.0);
  type("3");  // into the next field, which holds it until it is left
  EXPECT_TRUE(otherWrites.empty());
  press(kEnter);
  ASSERT_EQ(otherWrites.size(), 1u);
  EXPECT_EQ(storedOther, 3.0);
  EXPECT_EQ(writes.size(), 1u);
}

// The editor's case: typing into the inspector, then clicking a tree row that selects another
// part. The fields are drawn before the tree, so the field is left (and its number applied to the
// part it was typed for) before the click changes the selection.
TEST_F(TypedField, AClickOnARowDrawnAfterTheFieldAppliesTheNumberFirst) {
  frame(/*focus=*/true);
  frame();
  type("8");
  ImGuiIO& io = ImGui::GetIO();
  io.MousePos = ImVec2(450, 32);  // the tree's row
  io.MouseDown[0] = true;
  frame();
  io.MouseDown[0] = false;
  frame();
  EXPECT_TRUE(rowClicked);
  ASSERT_EQ(writes.size(), 1u);
  EXPECT_EQ(stored, 8.0);
}

// A double-click on a slider opens its text field at the value before its first press (which
// jumped the slider to the pointer), so that Escape keeps that value.
TEST_F(TypedField, ADoubleClickOnASliderTypesFromTheValueBeforeItsFirstPress) {
  ImGuiIO& io = ImGui::GetIO();
  io.MousePos = ImVec2(sliderMin.x + 5.0f, sliderMin.y + 5.0f);  // near 0, far from 50
  frame();
  for (int press = 0; press < 2; ++press) {
    io.MouseDown[0] = true;
    frame();
    if (press == 0) {
      EXPECT_LT(storedSlider, 20.0);  // the first press jumped it
    }
    io.MouseDown[0] = false;
    frame();
  }
  EXPECT_EQ(storedSlider, 50.0);
  type("7");
  EXPECT_EQ(storedSlider, 50.0);  // typed, not applied yet
  press(kEscape);
  EXPECT_EQ(storedSlider, 50.0);
}

TEST_F(TypedField, AClickElsewhereAppliesTheTypedNumber) {
  frame(/*focus=*/true);
  frame();
  type("-4.5");
  EXPECT_TRUE(writes.empty());
  ImGuiIO& io = ImGui::GetIO();
  io.MousePos = ImVec2(700, 500);  // outside the window
  io.MouseDown[0] = true;
  frame();
  io.MouseDown[0] = false;
  frame();
  ASSERT_EQ(writes.size(), 1u);
  EXPECT_EQ(stored, -4.5);
}

}  // namespace
}  // namespace strata::ui

namespace strata::ui {
namespace {

// A modifier's amount drags by a percent of itself a pixel (the scene's speed took a 2 mm offset
// to +10 mm in 60 pixels, through zero: an artist's test), never slower than the floor, and a
// drag from one side of zero stops there; a typed value (no drag) may cross it.
TEST(AmountDrag, APercentOfTheAmountAPixelStoppingAtZero) {
  const AmountDrag offset = amountDrag(-2.0, true, -1.0, 0.001);
  EXPECT_DOUBLE_EQ(offset.speed, 0.02);
  EXPECT_LE(60.0 * offset.speed, 1.5) << "60 pixels move a 2 mm offset by at most 1.5 mm";
  EXPECT_DOUBLE_EQ(offset.hi, 0.0) << "a shrink dragged up stops at zero";
  EXPECT_LT(offset.lo, -1e100);
  const AmountDrag grow = amountDrag(3.0, true, 1.0, 0.001);
  EXPECT_DOUBLE_EQ(grow.lo, 0.0);
  const AmountDrag typed = amountDrag(-2.0, true, 0.0, 0.001);
  EXPECT_LT(typed.lo, -1e100);
  EXPECT_GT(typed.hi, 1e100) << "typed, an offset may change side";
  const AmountDrag round = amountDrag(0.8, false, 1.0, 0.001);
  EXPECT_DOUBLE_EQ(round.lo, 1e-6);
  EXPECT_LE(40.0 * round.speed, 0.4);
  EXPECT_DOUBLE_EQ(amountDrag(0.0, true, 0.0, 0.001).speed, 0.001) << "the floor";
}

}  // namespace
}  // namespace strata::ui
