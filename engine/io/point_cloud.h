// Writing an LDI's surfels as a point cloud (binary little-endian PLY with normals and colours).
#pragma once

#include <glm/vec3.hpp>

#include <cstdint>
#include <functional>
#include <string>

#include "engine/ldi/ldi.h"

namespace strata {

// Writes the LDI's splats (engine/ldi/splats.h: every surfel on the axis its normal is most
// aligned with, so each patch of surface is written once, at an even density of one point per
// h^2 of projected area) as vertices with position (scene units), unit normal and the colour
// that `leafColor` gives its leaf (linear RGB in [0, 1], written as sRGB like every mesh
// writer). Written atomically; returns the number of points.
uint64_t writePointCloudPly(const Ldi& ldi, const std::string& path,
                            const std::function<glm::vec3(uint32_t leafId)>& leafColor);

}  // namespace strata
