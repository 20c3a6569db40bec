// The import dialog's options for a mesh file: the length unit its coordinates are in (scaled
// to the scene's unit) and which axis is up in it (Strata's up is +Z). Plain math; any thread.
#pragma once

#include <string>
#include <vector>

#include "engine/geometry/transform.h"

namespace strata::ui {

struct ImportUnit {
  const char* label;  // "millimetres"
  double metres;      // length of one unit in metres; 0 for "scene units" (no scaling)
};
// The units offered, "scene units" first.
const std::vector<ImportUnit>& importUnits();

// Metres per unit of a scene unit name ("millimetre", "mm", "inch", ...); 0 when unknown.
double sceneUnitMetres(const std::string& sceneUnit);

// What the view of an empty scene spans, in its unit: about a tenth of a metre (a hand-sized
// part: 100 mm, 10 cm, 3.9 in), at least one unit (1 m, 1 ft); 10 where the unit is unknown.
// New parts are a quarter of it (a millimetre scene's first box was 2 mm: the view showed 8 of
// its units whatever they were).
double emptySceneSpan(const std::string& sceneUnit);

// The factor from file units (importUnits()[unit]) to scene units. 1 for "scene units"; when
// the scene's unit is unknown, 1 with *why saying so.
double importScale(int unit, const std::string& sceneUnit, std::string* why);

// The mesh node's transform: uniform `scale`, and for upAxis 1 (+Y up in the file) a quarter
// turn about +X that takes +Y to +Z.
Transform importTransform(double scale, int upAxis);

}  // namespace strata::ui
