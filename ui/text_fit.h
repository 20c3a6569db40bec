// How a panel's text marks what it leaves out: text shortened to fit a width (the longest prefix
// of whole UTF-8 characters that, followed by an ellipsis, fits), text wrapped at spaces only,
// and a number field's format
// marked where the field shows its value rounded. Plain strings and a measuring function (pixels;
// ImGui::CalcTextSize in the panels), no ImGui here, so it is testable without a window.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace strata::ui {

// `text` when measure(text) <= width; else its longest prefix of whole characters followed by
// "\u2026" that fits; "\u2026" alone when not even one character fits. `measure` returns the width
// of a string in pixels and must not shrink when characters are appended.
std::string fitWithEllipsis(const std::string& text, float width,
                            const std::function<float(const std::string&)>& measure);

// `text` broken into lines no wider than `width` at spaces only (the spaces at a break dropped):
// Dear ImGui's wrapping also breaks after a '.' or a ',', and an estimate of "1.3 GiB of memory"
// ended a line with "1." and began the next with "3 GiB" (an artist's test). A word wider than
// `width` alone is a line of its own. A number is never the last word of a line ("844.2" and
// "MiB" apart): it stays with the word after it. `measure` as for fitWithEllipsis.
std::vector<std::string> wrapAtSpaces(const std::string& text, float width,
                                      const std::function<float(const std::string&)>& measure);

// The printf `format` of a number field (one %g, %f or %e conversion: "%.4g mm") for `value`,
// with a mark ("\u2026") after the number where the field shows it rounded: a field showed 16
// for 15.9694 and an artist took the hole to sit at exactly 16 mm (the whole number shows on
// hover). Noise (a millionth of the value, or of 1 near zero: a picked point's float precision)
// is not marked: "18…" for 18.0000005 after a drop read as a hidden fraction (an artist's test).
std::string markedWhereRounded(const std::string& format, double value);

// markedWhereRounded for the widest precision that fits the field: the format's %g or %f
// conversion given up to `mostDigits` significant digits (%g) or decimals (%f), the most that
// leave measure(the text) <= `room` (pixels), never fewer than the format's own. A field showed
// "18…" for 17.9994565 where "17.99946" fitted (an artist's test); numbers no longer than the
// format's own precision show as before.
std::string fittedNumberFormat(const std::string& format, double value, float room,
                               const std::function<float(const std::string&)>& measure,
                               int mostDigits = 7);

}  // namespace strata::ui
