// What the viewport draws of an LDI, prepared off the UI thread: every surfel once, on the axis
// its normal is most aligned with (ALGORITHM.md §6), as a compact record for a GL instance
// buffer; and the CPU pick against those records.
#pragma once

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

#include "engine/ldi/ldi.h"
#include "ui/camera.h"

namespace strata::ui {

// One splat: 20 bytes, laid out for glVertexAttrib(I)Pointer (see surfel.vert).
struct Splat {
  float position[3];  // world, scene units
  uint32_t normal;    // octahedral, as in Surfel
  uint32_t leafAxis;  // leaf id << 2 | axis of the ray it lies on
};
static_assert(sizeof(Splat) == 20, "tightly packed splat");

inline uint32_t splatLeaf(const Splat& s) {
  return s.leafAxis >> 2;
}

// The splats of `ldi` (any thread).
std::vector<Splat> buildSplats(const Ldi& ldi);

// The splat nearest along `ray` whose disc of `radius` (scene units) the ray passes through and
// whose normal faces the ray's origin. Returns false when none is hit.
struct SplatHit {
  uint32_t leaf = 0;
  glm::dvec3 position{0.0};
  double distance = 0.0;  // along the ray
};
bool pickSplat(const std::vector<Splat>& splats, const Ray& ray, double radius, SplatHit* hit);

}  // namespace strata::ui
