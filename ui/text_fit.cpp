#include "ui/text_fit.h"

#include <vector>

namespace strata::ui {

std::string fitWithEllipsis(const std::string& text, float width,
                            const std::function<float(const std::string&)>& measure) {
  if (measure(text) <= width) return text;
  static const std::string kEllipsis = "\u2026";
  // Where each whole character ends (a continuation byte, 10xxxxxx, never ends one).
  std::vector<size_t> ends;
  for (size_t i = 1; i <= text.size(); ++i)
    if (i == text.size() || (static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) ends.push_back(i);
  // Binary search for the longest prefix that fits with the ellipsis (widths grow with length).
  size_t lo = 0, hi = ends.size();  // prefixes of ends[0..lo) characters fit
  while (lo < hi) {
    const size_t mid = (lo + hi + 1) / 2;
    if (measure(text.substr(0, ends[mid - 1]) + kEllipsis) <= width)
      lo = mid;
    else
      hi = mid - 1;
  }
  // Trailing spaces before the ellipsis say nothing.
  size_t cut = lo == 0 ? 0 : ends[lo - 1];
  while (cut > 0 && text[cut - 1] == ' ') --cut;
  return text.substr(0, cut) + kEllipsis;
}

}  // namespace strata::ui
