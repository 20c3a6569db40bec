// The check of a binary STL written in pieces (streamed_export.h), in memory that does not grow
// with the mesh's vertices and edges: one pass over the file in its order.
//
// The streamed export writes its facets in the contour's edge order, the z index of each facet's
// grid edge never decreasing, and every vertex lies within the cell it was placed in (or on its
// faces): a vertex at z layer L (of the grid's cells) appears only in facets of edges below
// layer L + 3. The pass welds identical positions (as checkMesh does) within a window of a few
// layers, matches each edge's half-edges there, and lets a vertex and its edges go once the
// facets have moved kWindowLayers past it. It computes what checkMesh computes on the file's
// mesh (mesh_check.h), the same numbers: boundary, non-manifold and misoriented edges,
// degenerate triangles, edge-connected components (union-find over the facets: 8 bytes a facet,
// the one array that grows with the mesh), genus from each component's V - E + F, and the area
// and volume summed as checkMesh sums them (TriangleMeasures); the vertices counted are the
// distinct positions (checkMesh on the file read back; on an indexed mesh it counts the mesh's
// vertices, unused ones and ones at one position included). A vertex that came back
// after its window had passed (a file not written in that order) would count as new: its edges
// then show as boundary edges and the check fails; it never passes a file it could not check.
//
// Also the file's fingerprint (check_written.h), in the same pass.
//
// Synchronous; one thread (the file's decoding is parallel); `progress` receives stage "check"
// and is checked once per piece of the file read.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "engine/export/check_written.h"
#include "engine/geometry/mesh_check.h"
#include "engine/ldi/grid.h"
#include "engine/util/progress.h"

namespace strata {

// Layers a welded vertex stays after the facets' lowest possible edge layer has passed its own.
constexpr int kWindowLayers = 4;

// The measures above on facets fed in the file's order as they are written (the streamed
// export's write: check_written.h's split, where the mesh meant is measured beside the write and
// the file read back is compared with it by fingerprint), on a thread of its own. `facets`: how
// many will come; `grid`, (usedLo, usedHi): as below; `progress`: cancels it.
class StreamedMeshCheck {
 public:
  static constexpr size_t kQueuedBlocks = 4;  // add() waits while this many are queued
  StreamedMeshCheck(const Grid& grid, size_t facets, const glm::dvec3& usedLo,
                    const glm::dvec3& usedHi, const Progress& progress);
  ~StreamedMeshCheck();
  StreamedMeshCheck(const StreamedMeshCheck&) = delete;
  StreamedMeshCheck& operator=(const StreamedMeshCheck&) = delete;
  // A block of facets, three corners each as the file stores them.
  void add(std::vector<glm::dvec3> corners);
  // Waits for the measures; rethrows what stopped them (Cancelled included).
  MeshCheck finish();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// The check of the file written from the facets a StreamedMeshCheck measured (`measured`, its
// finish()): the file read back in pieces and fingerprinted against `expected` (the facets as
// stored, addToFingerprint); where they differ, the file read back raw and checked whole, as
// checkWrittenFile does.
WrittenCheck compareStreamedFile(const std::string& path, const MeshCheck& measured,
                                 const TriangleFingerprint& expected, Progress& progress);

// The whole check of a file on its own, read back in its order.
// `grid`: the export's; (usedLo, usedHi): the box of the vertices the facets use, as the file
// stores them (for the measures' frame); `expected`: the fingerprint of the facets written.
// Where the file's fingerprint differs, the file is read back raw and checked whole, as
// checkWrittenFile does. Throws strata::Error when the file cannot be read, Cancelled.
WrittenCheck checkStreamedStl(const std::string& path, const Grid& grid, const glm::dvec3& usedLo,
                              const glm::dvec3& usedHi, const TriangleFingerprint& expected,
                              Progress& progress);

}  // namespace strata
