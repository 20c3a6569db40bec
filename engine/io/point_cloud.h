// Writing an LDI's surfels as a point cloud (binary little-endian PLY with normals and colours).
#pragma once

#include <glm/vec3.hpp>

#include <cstdint>
#include <functional>
#include <string>

#include "engine/ldi/ldi.h"

namespace strata {

// Writes every surfel on the axis its normal is most aligned with (so each patch of surface
// is written once, at an even density of one point per h^2 of projected area), as a vertex
// with position (scene units), unit normal and the colour that `leafColor` gives its leaf
// (RGB in [0, 1]). Written atomically; returns the number of points.
uint64_t writePointCloudPly(const Ldi& ldi, const std::string& path,
                            const std::function<glm::vec3(uint32_t leafId)>& leafColor);

// World position of a surfel on ray `ray` of `axis`.
glm::dvec3 surfelPosition(const Grid& grid, int axis, int64_t ray, float depth);

// Calls visit(axis, surfel, unitNormal, worldPosition) for every surfel of `ldi` on the axis its
// normal is most aligned with (onDominantAxis): each patch of surface once, at an even density.
// What the point cloud writer and the editor's splats are made of.
void forEachDominantSurfel(const Ldi& ldi,
                           const std::function<void(int axis, const Surfel& s, const float n[3],
                                                    const glm::dvec3& p)>& visit);

}  // namespace strata
