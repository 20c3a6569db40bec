#include "app/cli_args.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "engine/util/error.h"

namespace strata {

CliArgs::CliArgs(const std::vector<std::string>& args, const std::vector<std::string>& valued,
                 const std::vector<std::string>& flags) {
  auto known = [](const std::vector<std::string>& list, const std::string& a) {
    return std::find(list.begin(), list.end(), a) != list.end();
  };
  for (size_t i = 0; i < args.size(); ++i) {
    std::string a = args[i];
    std::string value;
    bool inlineValue = false;
    if (a.rfind("--", 0) == 0 && a.find('=') != std::string::npos) {
      value = a.substr(a.find('=') + 1);
      a = a.substr(0, a.find('='));
      inlineValue = true;
    }
    if (known(valued, a)) {
      if (!inlineValue) {
        if (i + 1 >= args.size()) throw Error("option " + a + " needs a value");
        value = args[++i];
      }
      values_[a] = value;
    } else if (known(flags, a) && !inlineValue) {
      values_[a] = "";
    } else if (a.size() > 1 && a[0] == '-') {
      throw Error("unknown option " + args[i] + " (see strata --help)");
    } else {
      positional_.push_back(args[i]);
    }
  }
}

std::string CliArgs::text(const std::string& option, const std::string& fallback) const {
  auto it = values_.find(option);
  return it == values_.end() ? fallback : it->second;
}

int CliArgs::integer(const std::string& option, int fallback, int lo, int hi) const {
  auto it = values_.find(option);
  if (it == values_.end()) return fallback;
  char* end = nullptr;
  long v = std::strtol(it->second.c_str(), &end, 10);
  if (it->second.empty() || *end != '\0' || v < lo || v > hi)
    throw Error("option " + option + ": expected an integer in [" + std::to_string(lo) + ", " +
                std::to_string(hi) + "], got '" + it->second + "'");
  return int(v);
}

double CliArgs::number(const std::string& option, double fallback, double lo, double hi) const {
  auto it = values_.find(option);
  if (it == values_.end()) return fallback;
  char* end = nullptr;
  double v = std::strtod(it->second.c_str(), &end);
  if (it->second.empty() || *end != '\0' || !std::isfinite(v) || v < lo || v > hi)
    throw Error("option " + option + ": expected a number in [" + std::to_string(lo) + ", " +
                std::to_string(hi) + "], got '" + it->second + "'");
  return v;
}

}  // namespace strata
