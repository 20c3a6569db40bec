// The export dialog's choices remembered between runs: resolution, simplify and its tolerance,
// as "name value" lines in $XDG_CONFIG_HOME/strata/export.txt beside the panel layout (an
// artist who exports at 512 cells simplified found 256 unsimplified after a restart).
//
// Threads: the UI thread.
#pragma once

#include <string>

namespace strata::ui {

struct ExportSettings {
  int resolution = 0;  // cells along the longest side; 0: the document's, until chosen
  bool simplify = false;
  float simplifyCells = 0.25f;
};

// The settings saved in `path` over `defaults`; a missing or damaged file (or a line it does not
// know, or a value out of range) leaves the defaults.
ExportSettings readExportSettings(const std::string& path, ExportSettings defaults);
// Writes them atomically, creating the folder. Throws strata::Error.
void writeExportSettings(const std::string& path, const ExportSettings& settings);

}  // namespace strata::ui
