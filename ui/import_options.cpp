#include "ui/import_options.h"

#include <algorithm>
#include <cctype>

namespace strata::ui {

const std::vector<ImportUnit>& importUnits() {
  static const std::vector<ImportUnit> units = {{"scene units", 0.0},  {"millimetres", 0.001},
                                                {"centimetres", 0.01}, {"metres", 1.0},
                                                {"inches", 0.0254},    {"feet", 0.3048}};
  return units;
}

double sceneUnitMetres(const std::string& sceneUnit) {
  std::string u;
  for (char c : sceneUnit) u += char(std::tolower(static_cast<unsigned char>(c)));
  if (u == "millimetre" || u == "millimeter" || u == "mm") return 0.001;
  if (u == "centimetre" || u == "centimeter" || u == "cm") return 0.01;
  if (u == "metre" || u == "meter" || u == "m") return 1.0;
  if (u == "inch" || u == "in") return 0.0254;
  if (u == "foot" || u == "ft") return 0.3048;
  return 0.0;
}

double importScale(int unit, const std::string& sceneUnit, std::string* why) {
  const auto& units = importUnits();
  if (unit <= 0 || unit >= int(units.size())) return 1.0;
  const double scene = sceneUnitMetres(sceneUnit);
  if (scene <= 0.0) {
    if (why)
      *why = "the scene's unit '" + sceneUnit + "' is not a known length; the mesh is not scaled";
    return 1.0;
  }
  return units[size_t(unit)].metres / scene;
}

Transform importTransform(double scale, int upAxis) {
  Transform t;
  t.scale = glm::dvec3(scale);
  if (upAxis == 1) t.rotateDegrees = glm::dvec3(90.0, 0.0, 0.0);
  return t;
}

double emptySceneSpan(const std::string& sceneUnit) {
  const double metres = sceneUnitMetres(sceneUnit);
  return metres > 0.0 ? std::max(1.0, 0.1 / metres) : 10.0;
}

}  // namespace strata::ui
