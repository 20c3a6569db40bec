// Simplification of an export's mesh that keeps every guarantee of the export: edge collapses
// chosen by quadric error (OpenMesh's decimater, Debian's libopenmesh-dev), each refused when
// it would
//   - change the topology: OpenMesh's link condition (no non-manifold edge or vertex, no genus
//     or component change; a tetrahedron is never collapsed flat);
//   - fold a face over: no face normal may turn by more than kMaxNormalTurnDegrees;
//   - move the surface more than `tolerance`: every vertex of the unsimplified mesh stays within
//     `tolerance` of the simplified surface (as OpenMesh's Hausdorff module: the points of
//     removed vertices carried along on the faces that cover them), every simplified vertex is
//     one of the original ones, and the new faces stay within `tolerance` of the unsimplified
//     surface on a grid of points at most 3 tolerances apart. Between those points a face may
//     stray further: the deviation is then measured both ways (mesh_distance.h) and reported;
//   - blur a sharp feature: edges whose faces meet at more than kFeatureAngleDegrees, and edges
//     between triangles of different leaves (where one part meets another, which keeps each
//     part's colour on its own triangles), are features: a vertex on a feature may only slide
//     along a feature edge, and vertices where features meet or end do not move.
// Halfedge collapses keep the orientation; the leaf of every surviving triangle is kept.
// Flat regions collapse to a few large triangles (their quadric error is zero).
//
// Synchronous; parallel over chunks of the mesh (below), each through OpenMesh's sequential
// decimater; the result does not depend on the thread count. Progress stage
// "simplify"; a cancel is honoured within a few thousand collapses (milliseconds) and leaves
// `mesh` unchanged.
#pragma once

#include <cstddef>

#include "engine/geometry/export_mesh.h"
#include "engine/geometry/mesh_distance.h"
#include "engine/util/progress.h"

namespace strata {

constexpr double kFeatureAngleDegrees = 40.0;
constexpr double kMaxNormalTurnDegrees = 60.0;
constexpr double kSampleSpacingPerTolerance = 2.0;

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
