#include "ui/dialog_settings.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "engine/util/atomic_file.h"
#include "engine/util/limits.h"
#include "ui/import_options.h"

namespace strata::ui {

ExportSettings readExportSettings(const std::string& path, ExportSettings settings) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string name;
    double value = 0.0;
    if (!(words >> name >> value)) continue;
    if (name == "resolution" && value >= kMinResolution && value <= kMaxResolution)
      settings.resolution = int(value);
    if (name == "simplify" && (value == 0.0 || value == 1.0)) settings.simplify = value == 1.0;
    if (name == "simplifyCells" && value >= 0.05 && value <= 2.0)
      settings.simplifyCells = float(value);
  }
  return settings;
}

void writeExportSettings(const std::string& path, const ExportSettings& settings) {
  std::error_code ec;
  std::filesystem::create_directories(std::filesystem::path(path).parent_path(), ec);
  writeFileAtomically(path, [&](std::ostream& out) {
    out << "resolution " << settings.resolution << "\n"
        << "simplify " << (settings.simplify ? 1 : 0) << "\n"
        << "simplifyCells " << settings.simplifyCells << "\n";
  });
}

ImportSettings readImportSettings(const std::string& path, ImportSettings settings) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("folder ", 0) == 0) {
      settings.folder = line.substr(7);
      continue;
    }
    std::istringstream words(line);
    std::string name;
    int value = 0;
    if (!(words >> name >> value)) continue;
    if (name == "unit" && value >= 0 && size_t(value) < importUnits().size()) settings.unit = value;
    if (name == "upAxis" && (value == 0 || value == 1)) settings.upAxis = value;
  }
  return settings;
}

void writeImportSettings(const std::string& path, const ImportSettings& settings) {
  std::error_code ec;
  std::filesystem::create_directories(std::filesystem::path(path).parent_path(), ec);
  writeFileAtomically(path, [&](std::ostream& out) {
    // A folder whose name holds a line break cannot be kept on one line: left out.
    if (settings.folder.find_first_of("\r\n") == std::string::npos)
      out << "folder " << settings.folder << "\n";
    out << "unit " << settings.unit << "\n"
        << "upAxis " << settings.upAxis << "\n";
  });
}

}  // namespace strata::ui
