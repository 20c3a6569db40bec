// A scene: the document tree plus its settings, as stored in a *.strata.json file.
#pragma once

#include <glm/vec3.hpp>

#include <string>

#include "engine/document/measurement.h"
#include "engine/document/node.h"
#include "engine/util/limits.h"

namespace strata {

struct SceneSettings {
  int resolution = 256;  // cells along the longest side of the grid
  double margin = 0.05;  // grid margin around the scene bounds, as a fraction of their size
  std::string unit = "millimetre";  // length unit of scene coordinates (recorded in exports)
  // Optional explicit grid box; when set (min < max on every axis), the grid covers exactly this
  // box instead of the scene bounds plus margin.
  bool hasBounds = false;
  Bounds bounds;
  // Visible leaves an evaluation may visit through instances (engine/document/expansion.h).
  uint64_t maxLeaves = kDefaultMaxLeaves;
};

// "mm", "cm", "m", "in" for a scene's unit name (SceneSettings::unit); the name itself
// otherwise. The returned pointer lives as long as `unit`.
inline const char* unitSymbol(const std::string& unit) {
  if (unit == "millimetre" || unit == "millimeter") return "mm";
  if (unit == "centimetre" || unit == "centimeter") return "cm";
  if (unit == "metre" || unit == "meter") return "m";
  if (unit == "inch") return "in";
  return unit.c_str();
}

struct Scene {
  SceneSettings settings;
  NodePtr root;  // never null for a loaded scene
  // Distances and angles the artist placed (measurement.h); each point's part is in `root`.
  std::vector<Measurement> measurements;
};

}  // namespace strata
