// The export report: how the mesh was made, and the check of the file as written.
#pragma once

#include <string>
#include <vector>

#include "engine/export/export_scene.h"
#include "engine/geometry/mesh_check.h"

namespace strata {

struct ExportSummary {
  std::string input;
  std::string output;
  std::string unit;
  std::string backend;
  ExportReport result;                // the contour report and the check of the file as written
  std::vector<std::string> warnings;  // of the input, then the export's notices
  // Distributed exports (--distributed): the group and the tiles' wall time; "" otherwise.
  std::string distributed;
  double distributedTilesSeconds = 0.0;
  int processes = 1;
};

std::string formatExportText(const ExportSummary& s);
std::string formatExportJson(const ExportSummary& s);

}  // namespace strata
