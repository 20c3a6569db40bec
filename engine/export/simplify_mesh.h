// Simplification of an export's mesh that keeps every guarantee of the export: edge collapses
// onto the remaining vertex, cheapest quadric error first (Garland and Heckbert), on OpenMesh's
// halfedge mesh (Debian's libopenmesh-dev: its collapse and link test; the loop and the rules
// are ours, so that the costly rules run once per collapse that is due rather than for every
// candidate), each refused when it would
//   - change the topology: OpenMesh's link condition and its decimater's rules (no non-manifold
//     edge or vertex, no genus or component change; a tetrahedron is never collapsed flat);
//   - fold a face over: no face normal may turn by more than kMaxNormalTurnDegrees;
//   - move the surface more than `tolerance`: every vertex of the unsimplified mesh, the centre
//     of each of its triangles and the midpoint of each of its edges stays within `tolerance`
//     of the simplified face that covers it (the points carried along on the faces, as in
//     OpenMesh's Hausdorff module), and the new faces stay within `tolerance` of the
//     unsimplified surface on a grid of points 3 tolerances apart (at most 6 steps along an
//     edge: a large face is tested more coarsely). Between those points
//     either surface may stray a little further: the deviation is measured both ways
//     (mesh_distance.h) and reported;
//   - blur a sharp feature: edges whose faces meet at more than kFeatureAngleDegrees, and edges
//     between triangles of different leaves (where one part meets another, which keeps each
//     part's colour on its own triangles), are features: a vertex on a feature may only slide
//     along a feature edge, and vertices where features meet or end do not move.
// Then each free vertex moves along its normal onto the points its faces cover (the surface
// through them, not along their chords: the volume is kept), where every rule still holds.
// Halfedge collapses keep the orientation; the leaf of every surviving triangle is kept. Flat
// regions collapse to a few large triangles (their quadric error is zero).
//
// Synchronous; parallel over chunks of the mesh (below), each collapsed on one thread; the
// result does not depend on the thread count. Progress stage "simplify", never going back; a
// cancel is honoured within 1024 collapses (milliseconds) and leaves `mesh` unchanged.
#pragma once

#include <cstddef>

#include "engine/geometry/export_mesh.h"
#include "engine/geometry/mesh_distance.h"
#include "engine/util/progress.h"

namespace strata {

constexpr double kFeatureAngleDegrees = 40.0;
constexpr double kMaxNormalTurnDegrees = 60.0;
// The measured deviation samples each triangle this many tolerances apart (SimplifyReport).
constexpr double kSampleSpacingPerTolerance = 2.0;
// The deviation is measured up to this many tolerances; beyond, it is reported as capped.
constexpr double kMeasureReachPerTolerance = 2.0;

struct SimplifyReport {
  size_t trianglesBefore = 0;
  size_t trianglesAfter = 0;
  double tolerance = 0.0;  // the bound asked for (scene units)
  double seconds = 0.0;    // simplifying, measuring included
  // Measured after simplifying, both ways between the unsimplified and the simplified surface
  // (mesh_distance.h), samples kSampleSpacingPerTolerance * tolerance apart.
  SurfaceDeviation measured;
  // True when the mesh could not be put into OpenMesh's halfedge structure (a non-manifold
  // input); the mesh is then left as it was and `refusedWhy` says why.
  bool refused = false;
  const char* refusedWhy = "";
};

// Chunks simplified in parallel before the whole: slabs of about this many triangles (their
// number follows the mesh alone, so the result does not depend on the thread count), their seams
// locked, then the whole mesh with the seams free and the chunks' covered points carried over.
constexpr size_t kTrianglesPerChunk = size_t(1) << 17;

// Simplifies `mesh` in place within `tolerance` (scene units, > 0). Throws Cancelled.
SimplifyReport simplifyMesh(ExportMesh* mesh, double tolerance, Progress& progress,
                            size_t trianglesPerChunk = kTrianglesPerChunk);

}  // namespace strata
