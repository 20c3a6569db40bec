#include "ui/text_fit.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
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

std::vector<std::string> wrapAtSpaces(const std::string& text, float width,
                                      const std::function<float(const std::string&)>& measure) {
  std::vector<std::string> lines;
  std::string line;
  size_t at = 0;
  // The next word from `at` on ("" at a run of spaces), `at` moved past it and its space.
  const auto nextWord = [&] {
    const size_t space = text.find(' ', at);
    const size_t end = space == std::string::npos ? text.size() : space;
    const std::string word = text.substr(at, end - at);
    at = end + 1;
    return word;
  };
  // A number and the word after it stay together ("844.2 MiB" was broken after "844.2").
  const auto isNumber = [](const std::string& w) {
    bool digit = false;
    for (char c : w) {
      if (c >= '0' && c <= '9')
        digit = true;
      else if (c != '.' && c != ',' && c != '-' && c != '+')
        return false;
    }
    return digit;
  };
  while (at < text.size()) {
    std::string word = nextWord();
    if (word.empty()) continue;  // runs of spaces
    while (isNumber(word) && at < text.size()) {
      const std::string unit = nextWord();
      if (!unit.empty()) word += " " + unit;
      if (!isNumber(unit)) break;
    }
    if (line.empty()) {
      line = word;
    } else if (measure(line + " " + word) <= width) {
      line += " " + word;
    } else {
      lines.push_back(line);
      line = word;
    }
  }
  if (!line.empty() || lines.empty()) lines.push_back(line);
  return lines;
}

std::string markedWhereRounded(const std::string& format, double value) {
  char text[64];
  std::snprintf(text, sizeof(text), format.c_str(), value);
  // Noise of the numbers that placed it (a point picked on a surface carries the float
  // precision of the surfel it hit: 18.0000005 after a drop on a top at 8) is no hidden digit:
  // "18…" read as a fraction the field did not show (an artist's test).
  const double shown = std::strtod(text, nullptr);
  if (std::fabs(shown - value) <= 1e-6 * std::max(1.0, std::fabs(value))) return format;
  const size_t percent = format.find('%');
  const size_t conversion =
      percent == std::string::npos ? std::string::npos : format.find_first_of("gfeGFE", percent);
  if (conversion == std::string::npos) return format;
  return format.substr(0, conversion + 1) + "\u2026" + format.substr(conversion + 1);
}

std::string fittedNumberFormat(const std::string& format, double value, float room,
                               const std::function<float(const std::string&)>& measure,
                               int mostDigits) {
  const std::string own = markedWhereRounded(format, value);
  const size_t percent = format.find('%');
  if (percent == std::string::npos) return own;
  const size_t conversion = format.find_first_of("gfeGFE", percent);
  if (conversion == std::string::npos) return own;
  const char kind = format[conversion];
  if (kind != 'g' && kind != 'G' && kind != 'f' && kind != 'F') return own;
  // The format's own precision: "%.4g" 4, "%g" 6, "%.2f" 2.
  const size_t dot = format.find('.', percent);
  const int ownDigits =
      dot != std::string::npos && dot < conversion ? std::atoi(format.c_str() + dot + 1) : 6;
  const auto fitting = [&](int digits, bool* rounded) -> std::string {
    const std::string wider = format.substr(0, percent) + "%." + std::to_string(digits) + kind +
                              format.substr(conversion + 1);
    const std::string marked = markedWhereRounded(wider, value);
    char text[96];
    std::snprintf(text, sizeof(text), marked.c_str(), value);
    *rounded = marked != wider;
    return measure(text) <= room ? marked : std::string();
  };
  bool rounded = false;
  if (kind == 'g' || kind == 'G') {
    // %g drops trailing zeros: the most digits that fit show no more than the value needs.
    for (int digits = mostDigits; digits > ownDigits; --digits)
      if (std::string f = fitting(digits, &rounded); !f.empty()) return f;
    return own;
  }
  // %f pads with zeros: the fewest decimals that show the value whole, else the most that fit.
  if (own == format) return own;  // shown whole already
  std::string widest;
  for (int digits = ownDigits + 1; digits <= mostDigits; ++digits) {
    std::string f = fitting(digits, &rounded);
    if (f.empty()) break;
    widest = f;
    if (!rounded) return f;
  }
  return widest.empty() ? own : widest;
}

}  // namespace strata::ui
