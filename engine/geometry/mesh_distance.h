// The deviation between two triangle surfaces (one-sided Hausdorff distances, both ways), with
// a proven bound: each triangle of one surface is measured against the other by branch and
// bound (as in Guthe, Borodin and Klein, "Fast and accurate Hausdorff distance calculation
// between meshes", 2005). The distance from a point to the other surface is at most
//   - its distance at the nearest corner plus that corner's distance (1-Lipschitz): over a
//     triangle, the largest corner distance plus the farthest a point is from its nearest corner
//     (the circumradius of an acute triangle, else half the longest edge);
//   - its distance to any one triangle of the other surface, and that is a convex function, so
//     over a triangle it is largest at a corner: the candidates are the triangles nearest to
//     the three corners.
//   - for closed surfaces, in flat regions (where neither of the above is sharp: the other
//     surface there is many small triangles in one plane): the distance to that plane at the
//     corners, when every triangle of the other surface near the triangle lies close to that
//     plane and faces its way (a closed surface then has no edge or step there).
// A triangle whose bound exceeds `enough`, the largest corner distance found anywhere and its
// own corners' distances by more than `accuracy` is split in four, and so on. Used to report how
// far a simplified export lies from the surface it simplifies (simplify_mesh.h) and in tests.
//
// Synchronous; parallel inside (parallel_for.h); the result does not depend on the thread count.
#pragma once

#include <cstddef>

#include "engine/geometry/mesh.h"
#include "engine/geometry/triangle_grid.h"
#include "engine/util/progress.h"

namespace strata {

struct SurfaceDeviation {
  // The largest distance found at a point of `a` from `b`, and of `b` from `a` (scene units):
  // the true one-sided Hausdorff distances are at least these...
  double aToB = 0.0;
  double bToA = 0.0;
  // ...and at most these (proven), which exceed them by at most `accuracy` (or are at most
  // `enough`) unless `capped`.
  double aToBBound = 0.0;
  double bToABound = 0.0;
  double accuracy = 0.0;
  size_t samples = 0;  // points measured, both ways
  // True when some point has no triangle of the other surface within `cap`: its distance was
  // counted as `cap` (the true deviation is larger).
  bool capped = false;
  double largest() const { return aToB > bToA ? aToB : bToA; }
  double bound() const { return aToBBound > bToABound ? aToBBound : bToABound; }
};

// `closed`: both surfaces are closed (no boundary edge), which allows the flat-region bound.
// `accuracy` and `cap` are in the meshes' units (> 0); `enough` (>= 0, same units): bounds up to
// it need no sharper proof (a caller asking "within E?" passes a part of E). `aGrid` (may be null):
// a's triangles already in a grid whose reach is the cap. Progress stage `stage` from `from` to
// `to`, checked between blocks; throws Cancelled.
SurfaceDeviation measureDeviation(const TriangleMesh& a, const TriangleMesh& b, bool closed,
                                  double accuracy, double cap, double enough, Progress& progress,
                                  const char* stage = "measure deviation",
                                  const TriangleGrid* aGrid = nullptr, double from = 0.0,
                                  double to = 1.0);

}  // namespace strata
