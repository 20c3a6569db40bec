// Simplification of an export's mesh that keeps every guarantee of the export: edge collapses
// onto the remaining vertex, cheapest quadric error first (Garland and Heckbert), on OpenMesh's
// halfedge mesh (Debian's libopenmesh-dev: its collapse and link test; the loop and the rules
// are ours, so that the costly rules run once per collapse that is due rather than for every
// candidate), each refused when it would
//   - change the topology: OpenMesh's link condition and its decimater's rules (no non-manifold
//     edge or vertex, no genus or component change; a tetrahedron is never collapsed flat);
//   - fold a face over: no face normal may turn by more than kMaxNormalTurnDegrees;
//   - move the surface too far: every vertex of the unsimplified mesh, the centre of each of its
//     triangles and the midpoint of each of its edges stays within the rules' tolerance of the
//     simplified face that covers it (the points carried along on the faces, as in OpenMesh's
//     Hausdorff module), and the new faces stay within it of the unsimplified surface on a
//     grid of points 3 tolerances apart (at most 6 steps along an edge);
//   - blur a sharp feature: edges whose faces meet at more than kFeatureAngleDegrees, and edges
//     between triangles of different leaves (where one part meets another, which keeps each
//     part's colour on its own triangles), are features: a vertex on a feature may only slide
//     along a feature edge, and vertices where features meet or end do not move.
// Then each vertex that is not locked (free, or sliding on a feature) moves along its normal onto
// the points its faces cover (the surface through them, not along their chords: the volume is
// kept), where every rule still holds.
// The rules test points, so between them either surface may stray a little further: the result
// is measured (the Hausdorff distance both ways, with a proven bound: mesh_distance.h), and
// kept only when that bound is within `tolerance`; else the rules start again from the
// unsimplified mesh with a tolerance tighter by the overshoot (kMaxSimplifyAttempts in all).
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
// The measured deviation's proven bound exceeds the largest distance found by at most this many
// tolerances, or is at most kMeasureEnoughPerTolerance (SimplifyReport, mesh_distance.h).
constexpr double kMeasureAccuracyPerTolerance = 0.04;
// The rules' tolerance on the first attempt, as a share of the bound asked for: the rules test
// points, and between them the surfaces stray further (measured at 256 and 512 cells on the
// bundled demo and scaffolds and on armadillo - bunny: 1.3 to 1.7 times the rules' tolerance,
// the most at one large face of the scaffold). An overshoot is caught by the
// measurement and costs another attempt, not the bound.
constexpr double kFirstAttemptTolerance = 0.65;
constexpr int kMaxSimplifyAttempts = 4;
// Distances up to this many tolerances need no sharper proof (mesh_distance.h, `enough`).
constexpr double kMeasureEnoughPerTolerance = 0.9;
// The deviation is measured up to this many tolerances; beyond, it is reported as capped.
constexpr double kMeasureReachPerTolerance = 2.0;

struct SimplifyReport {
  size_t trianglesBefore = 0;
  size_t trianglesAfter = 0;
  double tolerance = 0.0;       // the bound asked for (scene units)
  double seconds = 0.0;         // simplifying, measuring included
  double measureSeconds = 0.0;  // of which measuring the deviation
  // Measured after simplifying, both ways between the unsimplified and the simplified surface
  // (mesh_distance.h), to within kMeasureAccuracyPerTolerance * tolerance; measured.bound() is
  // at most `tolerance` unless `refused`.
  SurfaceDeviation measured;
  int attempts = 0;                // 1 when the first attempt kept within the bound
  double rulesTolerance = 0.0;     // the collapse rules' tolerance on the last attempt
  double firstAttemptBound = 0.0;  // the proven deviation of the first attempt
  // True when the mesh could not be put into OpenMesh's halfedge structure (a non-manifold
  // input) or no attempt kept within the bound; the mesh is then left as it was and
  // `refusedWhy` says why.
  bool refused = false;
  const char* refusedWhy = "";
};

// Chunks simplified in parallel before the whole: slabs of about this many triangles (their
// number follows the mesh alone, so the result does not depend on the thread count), their seams
// locked; then slabs shifted by half a slab (the first seams inside them), in parallel; then the
// whole mesh with the seams free; the covered points carried from pass to pass.
constexpr size_t kTrianglesPerChunk = size_t(1) << 15;

// Simplifies `mesh` in place within `tolerance` (scene units, > 0). Throws Cancelled.
// `firstAttemptTolerance`: the rules' tolerance on the first attempt, in tolerances (tests).
SimplifyReport simplifyMesh(ExportMesh* mesh, double tolerance, Progress& progress,
                            size_t trianglesPerChunk = kTrianglesPerChunk,
                            double firstAttemptTolerance = kFirstAttemptTolerance);

}  // namespace strata
