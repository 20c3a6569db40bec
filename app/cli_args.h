// A small, strict command-line parser: every option must be known, every value well formed.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace strata {

class CliArgs {
 public:
  // `valued`: options that take a value (e.g. "--resolution", "-o"); `flags`: options without.
  // Throws strata::Error naming the offending argument, and where --report or --surfels would
  // write over an input, the output (-o) or each other.
  CliArgs(const std::vector<std::string>& args, const std::vector<std::string>& valued,
          const std::vector<std::string>& flags);

  const std::vector<std::string>& positional() const { return positional_; }
  bool has(const std::string& option) const { return values_.count(option) != 0; }
  std::string text(const std::string& option, const std::string& fallback) const;
  // An integer within [lo, hi]; Error otherwise.
  int integer(const std::string& option, int fallback, int lo, int hi) const;
  double number(const std::string& option, double fallback, double lo, double hi) const;

 private:
  // Refuses --report or --surfels naming an input, the output or each other (Error).
  void refuseSideFilesOverOthers() const;
  std::vector<std::string> positional_;
  std::map<std::string, std::string> values_;
};

}  // namespace strata
