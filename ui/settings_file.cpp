#include "ui/settings_file.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "engine/util/atomic_file.h"

namespace strata::ui {

void readSettingLines(
    const std::string& path,
    const std::function<void(const std::string& name, const std::string& value)>& visit) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const size_t space = line.find(' ');
    if (space == 0 || space == std::string::npos || space + 1 >= line.size()) continue;
    visit(line.substr(0, space), line.substr(space + 1));
  }
}

bool settingNumber(const std::string& value, double* out) {
  const char* begin = value.c_str();
  char* end = nullptr;
  const double v = std::strtod(begin, &end);
  if (end == begin || !std::isfinite(v)) return false;
  while (*end == ' ') ++end;
  if (*end != '\0') return false;
  *out = v;
  return true;
}

void writeSettingLines(const std::string& path,
                       const std::vector<std::pair<std::string, std::string>>& lines) {
  std::error_code ec;
  std::filesystem::create_directories(std::filesystem::path(path).parent_path(), ec);
  writeFileAtomically(path, [&](std::ostream& out) {
    for (const auto& [name, value] : lines)
      if (value.find_first_of("\r\n") == std::string::npos) out << name << " " << value << "\n";
  });
}

}  // namespace strata::ui
