// The file dialogs' choices remembered between runs, as "name value" lines beside the panel
// layout in $XDG_CONFIG_HOME/strata/: the export dialog's resolution, simplify and its tolerance
// (export.txt: an artist who exports at 512 cells simplified found 256 unsimplified after a
// restart), the import dialog's folder, unit and up axis (import.txt: an artist importing a
// folder of scans browsed to it again after every restart).
//
// Threads: the UI thread.
#pragma once

#include <string>

namespace strata::ui {

struct ExportSettings {
  int resolution = 0;  // cells along the longest side; 0: the document's, until chosen
  bool simplify = false;
  float simplifyCells = 0.25f;
  // The folder of the last export ("" = none yet): where an untitled document's first export of
  // a run is offered (an artist's first export of every run opened in $HOME), and a document
  // whose folder cannot be written to (a bundled scene).
  std::string folder;
};

// The settings saved in `path` over `defaults`; a missing or damaged file (or a line it does not
// know, or a value out of range) leaves the defaults. A folder line takes the rest of its line.
ExportSettings readExportSettings(const std::string& path, ExportSettings defaults);
// Writes them atomically, creating the folder. Throws strata::Error.
void writeExportSettings(const std::string& path, const ExportSettings& settings);

struct ImportSettings {
  std::string folder;  // where the last mesh was chosen from; "" = none yet
  int unit = 0;        // index into importUnits() (import_options.h)
  int upAxis = 0;      // 0: +Z up, 1: +Y up
};

// As readExportSettings: a folder line takes the rest of its line (spaces included); a unit
// outside importUnits() or an up axis other than 0 or 1 leaves the default.
ImportSettings readImportSettings(const std::string& path, ImportSettings defaults);
void writeImportSettings(const std::string& path, const ImportSettings& settings);

}  // namespace strata::ui
