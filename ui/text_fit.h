// Text shortened to fit a width: the longest prefix of whole UTF-8 characters that, followed by
// an ellipsis, fits. Plain strings and a measuring function (pixels; ImGui::CalcTextSize in the
// panels), no ImGui here, so it is testable without a window.
#pragma once

#include <functional>
#include <string>

namespace strata::ui {

// `text` when measure(text) <= width; else its longest prefix of whole characters followed by
// "\u2026" that fits; "\u2026" alone when not even one character fits. `measure` returns the width
// of a string in pixels and must not shrink when characters are appended.
std::string fitWithEllipsis(const std::string& text, float width,
                            const std::function<float(const std::string&)>& measure);

}  // namespace strata::ui
