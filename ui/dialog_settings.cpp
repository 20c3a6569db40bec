#include "ui/dialog_settings.h"

#include <cmath>
#include <sstream>

#include "engine/util/limits.h"
#include "ui/import_options.h"
#include "ui/settings_file.h"

namespace strata::ui {
namespace {
std::string text(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}
}  // namespace

ExportSettings readExportSettings(const std::string& path, ExportSettings settings) {
  readSettingLines(path, [&](const std::string& name, const std::string& text) {
    if (name == "folder") {
      settings.folder = text;
      return;
    }
    double value = 0.0;
    if (!settingNumber(text, &value)) return;
    if (name == "resolution" && value >= kMinResolution && value <= kMaxResolution)
      settings.resolution = int(value);
    if (name == "simplify" && (value == 0.0 || value == 1.0)) settings.simplify = value == 1.0;
    if (name == "simplifyCells" && value >= 0.05 && value <= 2.0)
      settings.simplifyCells = float(value);
  });
  return settings;
}

void writeExportSettings(const std::string& path, const ExportSettings& settings) {
  writeSettingLines(path, {{"resolution", std::to_string(settings.resolution)},
                           {"simplify", settings.simplify ? "1" : "0"},
                           {"simplifyCells", text(settings.simplifyCells)},
                           {"folder", settings.folder}});
}

ImportSettings readImportSettings(const std::string& path, ImportSettings settings) {
  readSettingLines(path, [&](const std::string& name, const std::string& text) {
    if (name == "folder") {
      settings.folder = text;
      return;
    }
    double value = 0.0;
    if (!settingNumber(text, &value) || value != std::floor(value)) return;
    if (name == "unit" && value >= 0 && size_t(value) < importUnits().size())
      settings.unit = int(value);
    if (name == "upAxis" && (value == 0 || value == 1)) settings.upAxis = int(value);
  });
  return settings;
}

void writeImportSettings(const std::string& path, const ImportSettings& settings) {
  writeSettingLines(path, {{"folder", settings.folder},
                           {"unit", std::to_string(settings.unit)},
                           {"upAxis", std::to_string(settings.upAxis)}});
}

}  // namespace strata::ui
