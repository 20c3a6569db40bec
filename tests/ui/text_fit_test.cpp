// Names shortened with an ellipsis to fit the outliner's column (ui/text_fit.h).
#include <gtest/gtest.h>

#include <algorithm>

#include "ui/text_fit.h"

namespace strata::ui {
namespace {

// Every character (a whole UTF-8 sequence) is 10 pixels wide.
float charWidth(const std::string& s) {
  float w = 0.0f;
  for (unsigned char c : s)
    if ((c & 0xC0) != 0x80) w += 10.0f;
  return w;
}

TEST(TextFit, ShortTextIsKeptAndLongTextEndsWithAnEllipsisThatFits) {
  EXPECT_EQ(fitWithEllipsis("plate", 50.0f, charWidth), "plate");
  EXPECT_EQ(fitWithEllipsis("rounded plate", 60.0f, charWidth), "round\u2026");
  EXPECT_LE(charWidth(fitWithEllipsis("rounded plate", 60.0f, charWidth)), 60.0f);
  // A space before the cut is dropped: "rounded\u2026", not "rounded \u2026".
  EXPECT_EQ(fitWithEllipsis("rounded plate", 90.0f, charWidth), "rounded\u2026");
  EXPECT_EQ(fitWithEllipsis("rounded plate", 5.0f, charWidth), "\u2026");
}

TEST(TextFit, CutsOnlyBetweenWholeCharacters) {
  const std::string name =
      "\u0434\u0435\u0442\u0430\u043b\u044c \u2116 7";  // Cyrillic, two bytes each
  const std::string fit = fitWithEllipsis(name, 40.0f, charWidth);
  EXPECT_EQ(fit, "\u0434\u0435\u0442\u2026");
  EXPECT_EQ(fitWithEllipsis(name, 1000.0f, charWidth), name);
}

// An estimate wrapped at spaces only: "1.3 GiB" is never parted at its point, as ImGui's own
// wrapping parted it (an artist's test); every line fits, and the words come back joined.
TEST(TextFit, TextWrapsAtSpacesOnlyAndNeverInsideANumber) {
  const std::string estimate =
      "467 x 410 x 1024 cells, about 3.9 million triangles, 1.3 GiB of memory, a 186.9 MiB "
      "file, 7 s";
  // "1024 cells," (a number stays with its word) is 110 wide.
  for (float width = 110.0f; width <= 400.0f; width += 10.0f) {
    SCOPED_TRACE(width);
    const std::vector<std::string> lines = wrapAtSpaces(estimate, width, charWidth);
    std::string joined;
    for (const std::string& line : lines) {
      EXPECT_LE(charWidth(line), width) << line;
      EXPECT_NE(line.front(), ' ');
      EXPECT_NE(line.back(), ' ');
      EXPECT_NE(line.back(), '.') << "a line ends inside a number";
      EXPECT_FALSE(line.back() >= '0' && line.back() <= '9') << "a number apart from its unit";
      joined += (joined.empty() ? "" : " ") + line;
    }
    EXPECT_EQ(joined, estimate);
  }
  EXPECT_EQ(wrapAtSpaces("1.3 GiB of memory", 90.0f, charWidth),
            (std::vector<std::string>{"1.3 GiB", "of memory"}));
  EXPECT_EQ(wrapAtSpaces("", 80.0f, charWidth), std::vector<std::string>{""});
  EXPECT_EQ(wrapAtSpaces("a abcdefghij b", 50.0f, charWidth),
            (std::vector<std::string>{"a", "abcdefghij", "b"}));  // wider than the line: alone
  EXPECT_EQ(wrapAtSpaces("a 1234567890 b", 50.0f, charWidth),
            (std::vector<std::string>{"a", "1234567890 b"}));  // a number with its word
  EXPECT_EQ(wrapAtSpaces("memory 844.2 MiB", 90.0f, charWidth),
            (std::vector<std::string>{"memory", "844.2 MiB"}));
}

// A number field marks a value it shows rounded, not one whose only difference is rounding
// noise (an artist read "18…" for a drop's 18.000000000000004 as a hidden fraction).
TEST(TextFit, ARoundedNumberIsMarkedAndRoundingNoiseIsNot) {
  EXPECT_EQ(markedWhereRounded("%.4g mm", 15.9694), "%.4g\u2026 mm");
  EXPECT_EQ(markedWhereRounded("%.4g mm", 16.0), "%.4g mm");
  EXPECT_EQ(markedWhereRounded("%.4g mm", 18.000000000000004), "%.4g mm");
  EXPECT_EQ(markedWhereRounded("%.4g mm", 18.0000005), "%.4g mm");  // a float's precision
  EXPECT_EQ(markedWhereRounded("%.4g mm", 18.0002), "%.4g\u2026 mm");
  EXPECT_EQ(markedWhereRounded("%.4g mm", 0.1 + 0.2), "%.4g mm");
  EXPECT_EQ(markedWhereRounded("%.4g", -9.6213), "%.4g\u2026");
  EXPECT_EQ(markedWhereRounded("%.2f deg", 37.2134), "%.2f\u2026 deg");
  EXPECT_EQ(markedWhereRounded("%.4g mm", 1e-7), "%.4g mm");  // shown as it is: 1e-07
  EXPECT_EQ(markedWhereRounded("%.4g mm", 12345.678), "%.4g\u2026 mm");
}

// A field shows as many digits as its room allows, up to seven: "18…" for 17.9994565 in a field
// where "17.99946" fits (an artist's test); fewer where the room is less, the format's own
// where none more fit; %f with the fewest decimals that show the value whole.
TEST(TextFit, ANumberFieldShowsTheDigitsItHasRoomFor) {
  const auto sevenWide = [](const std::string& s) {  // 7 pixels a character (not a byte)
    return 7.0f *
           float(std::count_if(s.begin(), s.end(), [](char c) { return (c & 0xC0) != 0x80; }));
  };
  // "17.99946": within a millionth of the value, no mark (markedWhereRounded's noise).
  EXPECT_EQ(fittedNumberFormat("%.4g", 17.9994565, 70.0f, sevenWide), "%.7g");
  EXPECT_EQ(fittedNumberFormat("%.4g mm", 17.9994565, 7.0f * 11, sevenWide), "%.7g mm");
  EXPECT_EQ(fittedNumberFormat("%.4g", 17.9994565, 7.0f * 7, sevenWide), "%.5g\u2026");  // 17.999…
  EXPECT_EQ(fittedNumberFormat("%.4g", 17.9994565, 7.0f * 3, sevenWide), "%.4g\u2026");
  EXPECT_EQ(fittedNumberFormat("%.4g", 17.5, 70.0f, sevenWide), "%.7g");  // "17.5" as before
  EXPECT_EQ(fittedNumberFormat("%.4g", 9.475, 70.0f, sevenWide), "%.7g");
  EXPECT_EQ(fittedNumberFormat("%.2f deg", 37.2134, 200.0f, sevenWide), "%.4f deg");
  EXPECT_EQ(fittedNumberFormat("%.2f deg", 37.2134, 7.0f * 11, sevenWide), "%.4f deg");
  EXPECT_EQ(fittedNumberFormat("%.2f deg", 37.2134567, 7.0f * 11, sevenWide), "%.3f\u2026 deg");
  EXPECT_EQ(fittedNumberFormat("%.2f deg", 37.2134, 7.0f * 10, sevenWide), "%.2f\u2026 deg");
  EXPECT_EQ(fittedNumberFormat("%.2f deg", 90.0, 200.0f, sevenWide), "%.2f deg");
  // 0.333333: within a millionth of 1 of a third, shown as whole.
  EXPECT_EQ(fittedNumberFormat("%.2f deg", 1.0 / 3.0, 200.0f, sevenWide), "%.6f deg");
}

}  // namespace
}  // namespace strata::ui
