// The export report: how the mesh was made, and the check of the file as written.
#pragma once

#include <string>
#include <vector>

#include "engine/export/contour_scene.h"
#include "engine/geometry/mesh_check.h"

namespace strata {

struct ExportSummary {
  std::string input;
  std::string output;
  std::string unit;
  std::string backend;
  ContourReport contour;
  double writeSeconds = 0.0;
  double checkSeconds = 0.0;
  MeshCheck check;  // of the file re-read from disk
  std::vector<std::string> warnings;
};

// True when the re-read file is a closed, manifold, consistently oriented mesh with positive
// volume, finite coordinates and no degenerate triangles.
bool exportCheckPassed(const MeshCheck& check);

std::string formatExportText(const ExportSummary& s);
std::string formatExportJson(const ExportSummary& s);

}  // namespace strata
