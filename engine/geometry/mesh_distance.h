// The deviation between two triangle surfaces, measured by sampling (like the Metro tool):
// points on every triangle of one surface, at most `spacing` apart (its corners included), each
// measured to the nearest triangle of the other, both ways. Used to report how far a
// simplified export lies from the surface it simplifies (simplify_mesh.h) and in tests.
//
// Synchronous; parallel inside (parallel_for.h); the result does not depend on the thread count.
#pragma once

#include <cstddef>

#include "engine/geometry/mesh.h"
#include "engine/geometry/triangle_grid.h"
#include "engine/util/progress.h"

namespace strata {

struct SurfaceDeviation {
  double aToB = 0.0;  // the largest distance of a sample of `a` from `b` (scene units)
  double bToA = 0.0;
  double spacing = 0.0;  // samples on each triangle at most this far apart along its edges
  size_t samples = 0;
  // True when some sample has no triangle of the other surface within `cap`: its distance was
  // counted as `cap` (the true deviation is larger).
  bool capped = false;
  double largest() const { return aToB > bToA ? aToB : bToA; }
};

// `spacing` and `cap` are in the meshes' units (> 0). A point of a triangle is at most
// spacing / sqrt(3) from its nearest sample, so the true deviation exceeds the measured one by
// at most that. `aGrid` (may be null): a's triangles already in a grid whose reach is the cap.
// Progress stage `stage` from `from` to `to`, checked between blocks; throws Cancelled.
SurfaceDeviation measureDeviation(const TriangleMesh& a, const TriangleMesh& b, double spacing,
                                  double cap, Progress& progress,
                                  const char* stage = "measure deviation",
                                  const TriangleGrid* aGrid = nullptr, double from = 0.0,
                                  double to = 1.0);

}  // namespace strata
