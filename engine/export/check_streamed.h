// The check of a binary STL or PLY written in pieces (streamed_export.h), in memory that does not
// grow with the mesh's vertices and edges: the facets measured in the file's order as they are
// written, in runs ("chunks") on several threads.
//
// The streamed export writes its facets in the contour's edge order, the z index of each facet's
// grid edge never decreasing, and every vertex lies within the cell it was placed in (or on its
// faces): a facet of edge layer E has its corners in layers E - 1 .. E + 1. Each chunk welds
// identical positions (as checkMesh does) within a window of a few layers, matches each edge's
// half-edges there, and lets a vertex and its edges go once the facets have moved kWindowLayers
// past it. A vertex that may also be used by another chunk (one at or below the highest layer
// of any corner before the chunk, or still in the window at the chunk's end) is "open": it, and
// each edge between two vertices open on the same side (both used before the chunk, or both
// still there at its end), are handed on, and a window of its own over them, in chunk order,
// welds them by position across chunks and counts them. The result is
// what checkMesh computes on the file's mesh (mesh_check.h), the same numbers, whatever the
// chunks: boundary, non-manifold and misoriented edges, degenerate triangles, edge-connected
// components (union-find over the facets: 8 bytes a facet, the one array that grows with the
// mesh), genus from each component's V - E + F, and the area and volume summed as checkMesh
// sums them (TriangleMeasures); the vertices counted are the distinct positions (checkMesh on the
// file read back; on an indexed mesh it counts the mesh's vertices, unused ones and ones at one
// position included; the streamed PLY's report gives the file's vertex count). A PLY's facets
// are matched by position too, as an STL's: by index but where two of its vertices share a
// position. A vertex that came back after its window had passed (a file not written in
// that order) counts as new: its edges then show as boundary edges and the check fails; it never
// passes a file it could not check.
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
// The facets of a chunk of the check (a multiple of kMeasureBlock): about 128 of the grid's z
// layers' worth (facets / layers x 128, so that its open vertices, within a few layers of its
// two ends, are a small share), from 8 to 32 measure blocks (9 to 38 MB of corners).
size_t streamedCheckChunkFacets(const Grid& grid, size_t facets);
// The threads of the check, sharing the cores with the writer's (which encodes on all of
// them): one fewer than workerCount() up to 4, and up to 8 where half the cores are more (each
// holds a window of vertices and a chunk of corners:
// about 0.1 GB at 4096 cells; on the 16-core H200 host 8 threads wrote armadillo - bunny's 72 M
// facets in 5.6-5.8 s against 6.7-7.5 with 4, 12 no faster, the peak 2.1 -> 2.5 GB); one where
// there are two cores or fewer.
int streamedCheckThreads();
// The bytes of corners the check holds at most (streamedCheckThreads' threads), float32 or
// `doubles`.
uint64_t streamedCheckBytes(const Grid& grid, size_t facets, bool doubles = false);

// The measures above on facets fed in the file's order as they are written (the streamed
// export's write: check_written.h's split, where the mesh meant is measured beside the write and
// the file read back is compared with it by fingerprint), on threads of their own: chunks of
// `chunkFacets` facets (a positive multiple of kMeasureBlock; 0: streamedCheckChunkFacets, or
// all of them on one thread) on `threads` threads (0: streamedCheckThreads), each chunk taken by
// a thread as its first block comes and measured as the rest come. Facets added and not yet
// measured (12 bytes a corner) are held up to threads + 1 chunks (one thread: 8 measure blocks);
// add() waits beyond that.
// `facets`: how many will come; `grid`: the export's; (usedLo, usedHi): the box of the vertices
// the facets use, as the file stores them (the measures' frame); `progress`: cancels it.
class StreamedMeshCheck {
 public:
  StreamedMeshCheck(const Grid& grid, size_t facets, const glm::dvec3& usedLo,
                    const glm::dvec3& usedHi, const Progress& progress, size_t chunkFacets = 0,
                    int threads = 0);
  ~StreamedMeshCheck();
  StreamedMeshCheck(const StreamedMeshCheck&) = delete;
  StreamedMeshCheck& operator=(const StreamedMeshCheck&) = delete;
  // A block of facets, three corners each as the file stores them (binary STL: float32; PLY:
  // double). Waits while as many chunks as allowed are held.
  void add(std::vector<glm::vec3> corners);
  void add(std::vector<glm::dvec3> corners);
  // Waits for the measures; rethrows what stopped them (Cancelled included).
  MeshCheck finish();

 private:
  template <typename Corner>
  void addCorners(std::vector<Corner> corners);
  struct State;
  std::unique_ptr<State> state_;
};

// The check of the file written from the facets `measures` measured: the file read back in
// pieces and fingerprinted against `expected` (the facets as stored, addToFingerprint) on a
// thread of its own while the measures finish (measures.finish(), on this one); where they
// differ, the file read back raw and checked whole, as checkWrittenFile does. Rethrows what
// stopped either (the measures' first).
WrittenCheck compareStreamedFile(const std::string& path, StreamedMeshCheck& measures,
                                 const TriangleFingerprint& expected, Progress& progress);

}  // namespace strata
