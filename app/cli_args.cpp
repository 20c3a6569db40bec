#include "app/cli_args.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

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
  refuseSideFilesOverOthers();
}

namespace {

// Whether paths `a` and `b` name one file (the same file through links or another spelling, or
// the same place where neither exists yet).
bool sameFile(const std::string& a, const std::string& b) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec);
  const fs::path pa = fs::weakly_canonical(fs::absolute(a, ec), ec);
  const fs::path pb = fs::weakly_canonical(fs::absolute(b, ec), ec);
  return pa == pb;
}

}  // namespace

void CliArgs::refuseSideFilesOverOthers() const {
  // The output itself may replace its input (it is read first); a report or the surfels written
  // over the input, the output or each other would lose one of them.
  for (const char* side : {"--report", "--surfels"}) {
    auto it = values_.find(side);
    if (it == values_.end() || it->second.empty()) continue;
    const std::string& path = it->second;
    for (const std::string& input : positional_)
      if (sameFile(path, input))
        throw Error(std::string(side) + " " + path + ": the same file as the input " + input +
                    ", which it would replace: give it a file of its own");
    for (const char* other : {"-o", "--output", "--report", "--surfels"}) {
      auto o = values_.find(other);
      if (other == std::string(side) || o == values_.end() || o->second.empty()) continue;
      if (sameFile(path, o->second))
        throw Error(std::string(side) + " " + path + ": the same file as " + other +
                    ": each output needs a file of its own");
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
  if (it->second.empty() || *end != '\0' || !std::isfinite(v) || v < lo || v > hi) {
    // The range as people write numbers ("1e-09", "1e+09"; not 300 digits, nor 0.000000 for a
    // least value above zero).
    char range[96];
    std::snprintf(range, sizeof(range), "from %.6g to %.6g", lo, hi);
    throw Error("option " + option + ": expected a number " + range + ", got '" + it->second + "'");
  }
  return v;
}

}  // namespace strata
