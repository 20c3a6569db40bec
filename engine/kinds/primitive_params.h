// The parameters of a primitive leaf. Which fields a primitive reads, their names, units and
// ranges are in its table entry (primitives.h); every consumer (scene files, validation, cache
// keys, the inspector) iterates over that entry rather than over these fields.
#pragma once

#include <glm/vec3.hpp>

namespace strata {

// Lengths in scene units.
struct PrimitiveParams {
  glm::dvec3 size{1.0};
  double radius = 0.5;
  double topRadius = 0.0;
  double height = 1.0;
  double majorRadius = 1.0;
  double minorRadius = 0.25;
  // Tessellation level of detail: segments around the circumference; 0 = automatic, chosen
  // from the grid's cell size so that the chordal error stays below 1/50 of a cell.
  int segments = 0;

  bool operator==(const PrimitiveParams& o) const {
    return size == o.size && radius == o.radius && topRadius == o.topRadius && height == o.height &&
           majorRadius == o.majorRadius && minorRadius == o.minorRadius && segments == o.segments;
  }
};

}  // namespace strata
