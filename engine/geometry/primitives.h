// Tessellation of the primitive leaves into closed, outward-oriented triangle meshes.
#pragma once

#include "engine/document/node.h"
#include "engine/geometry/mesh.h"

namespace strata {

// Segments around the circumference for a primitive whose largest radius, after its world
// transform, is `worldRadius` scene units, such that the chordal error stays below
// `maxError` scene units. Clamped to [12, kMaxAutoSegments].
int autoSegments(double worldRadius, double maxError);
constexpr int kMaxAutoSegments = 1024;
// The most segments a primitive may ask for explicitly (scene files, the inspector).
constexpr int kMaxSegments = 4096;

// The primitive's mesh in object coordinates (centred at the origin, axis along z), with
// `segments` segments around (>= 3). Box ignores segments. Throws strata::Error for a
// non-primitive kind or invalid parameters.
TriangleMesh tessellatePrimitive(NodeKind kind, const PrimitiveParams& params, int segments);

// The largest radius of the primitive in object units (0 for a box): what autoSegments needs,
// times the transform's largest scale.
double primitiveRadius(NodeKind kind, const PrimitiveParams& params);

}  // namespace strata
