// A watertight export written in pieces, for meshes larger than the memory that holds them
// (`strata export SCENE -o OUT.stl --stream`).
//
// The single-process export (export_scene.h) holds every tile's vertices and triangles and then
// the whole indexed mesh (about 90 bytes a triangle at its peak). This one contours the tiles a
// slab at a time (the tiles sharing a z index, in increasing z), merges each slab into an
// indexed piece (contour_scene.h: mergeTiles) and spills it to a scratch file beside the output
// (unlinked at once: nothing is left behind, whatever happens), keeping in memory only what
// the component steps need across pieces: one 32-bit set per vertex of the whole mesh (its
// component, by union-find over the global vertex keys that neighbouring slabs share) and one
// record per component. Later passes over the scratch file replay the component steps exactly
// as the single-process export runs them on the whole mesh, in the same global orders and
// with the same sums (unfold_shells.h: the shells' six volumes in the same chunks and runs;
// drop_specks.h: the same rule per component; degenerate_repair.h on the neighbourhood of the
// flawed triangles, grown until it holds every triangle around each corner the repair reads),
// then write the file a piece at a time. The file is the single-process export's, byte for byte.
// Each later pass reads the next piece on a thread of its own while it works on one, in parallel
// over blocks of the piece's triangles (parallel_for.h), taking the blocks' results in order
// where the order counts (the shells' sums: ShellRunSums, unfold_shells.h; the facets written):
// the same file on any thread count.
//
// Memory: the tiles and piece of the slab being merged (streamedTiling below), the tiles of the
// slabs the workers contour meanwhile (streamedSlabsAhead), the piece before while it is
// spilled and two pieces in the later passes, plus about 8 bytes a vertex of the whole mesh
// (sets and counts; a PLY 8 more: its index, colour and state) and, for the check, 8 bytes a
// triangle; disk: the scratch file, about 36 bytes a triangle (a PLY 40: each triangle's leaf),
// beside the output.
//
// Formats: binary STL (.stl), whose facets are written in order as they come, and binary PLY
// (.ply), whose vertices come first: a pass over the pieces numbers the vertices the kept
// triangles use (before the repair, as dropUnresolvedSpecks keeps them) in key order, the ids
// of the vertices shared by neighbouring slabs being those of their global keys, and colours
// each by the leaf of the first triangle (after the repair) that uses it; then the vertices are
// written a piece at a time, each where its key first came, and the faces as STL's facets.
// That file is the in-memory export's too, byte for byte. OBJ and 3MF are refused; --simplify
// needs the whole mesh and is refused. The check (check_streamed.h) measures the facets as
// checkMesh would, on a thread of its own as they are written, and then reads the file back in
// pieces (a PLY's faces a piece at a time, the vertices they use a page at a time) to compare
// its fingerprint with the one accumulated while writing.
//
// Synchronous (the tiles contoured on worker threads, a slab or so ahead of the merge on the
// calling thread: exportSceneStreamed below); progress stages "export" (a step per tile), "merge"
// (the passes over the pieces), "write STL" (or "write PLY") and "check", checked between and
// within them. Throws
// strata::Error naming `path`, or Cancelled; the file is written atomically (nothing is replaced
// unless the write completes).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "engine/contour/contour_tile.h"
#include "engine/eval/backend.h"
#include "engine/export/contour_scene.h"
#include "engine/export/export_scene.h"
#include "engine/export/fallback.h"
#include "engine/util/progress.h"

namespace strata {

// The tiling a streamed export uses: slabs of the grid's whole x and y extent, at least
// kStreamedSlabs of them, each window holding no more nodes than a tile of exportTiling's (what
// the backend's memory allows) and its cells indexed in 32 bits; exportTiling's cubes where
// such slabs would be thinner than kMinStreamedTile cells, or where options.tileCells sets the
// tile; cubes no larger than exportTiling's in at least kStreamedSlabs layers where the slabs'
// windows would evaluate more than kStreamedHaloWork times the grid's nodes and more than the
// cubes' (ExportTiling::evaluatedNodes: a modifier's halo around thin slabs). A slab's tiles and
// piece are what the export holds at once.
constexpr int kStreamedSlabs = 8;
constexpr int kMinStreamedTile = 16;
constexpr double kStreamedHaloWork = 2.0;
ExportTiling streamedTiling(const Scene& scene, const ContourOptions& options, uint64_t memoryBytes,
                            uint64_t offsetBytesPerNode);

// Why `path` and `options` cannot be streamed ("" when they can).
std::string streamedExportRefusal(const std::string& path, const ExportOptions& options);

// The export's pieces as they come, for a caller that contours the tiles itself (the
// distributed export's process 0, distributed_export.h): addSlab(z, tiles) with every tile of
// slab z (tiles numbered as ExportTiling numbers them: z = t / (counts.x * counts.y)), slabs in
// increasing z, then finish() (the passes, the write, the check into *report). `tiling`: the
// export's (streamedTiling); report->contour gets the merge's counts and times, the caller's
// tiles' counters are the caller's to add. Throws as exportSceneStreamed.
class StreamedExportWriter {
 public:
  StreamedExportWriter(const Scene& scene, const std::string& path, const ExportOptions& options,
                       const ExportTiling& tiling, Progress& progress, ExportReport* report);
  ~StreamedExportWriter();
  StreamedExportWriter(const StreamedExportWriter&) = delete;
  StreamedExportWriter& operator=(const StreamedExportWriter&) = delete;
  void addSlab(int z, std::vector<TileContour> tiles);
  void finish();

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

// How many of a tiling's `slabs` the workers contour ahead of the one the writer merges: one a
// worker, but no more than an eighth of the slabs (at least one), so that the tiles held stay a
// small share of the mesh however many workers there are (the estimate counts them:
// streamedPeakOnWorkers, job_estimate.h).
int streamedSlabsAhead(int workers, int slabs);

// The export on `backends`, one worker thread each (contour_workers.h: TileWorkers;
// `workersPerMemory` of them share one backend's memory), while the calling thread merges each
// slab as its last tile comes in: the same file as on one backend. `notice` (may be empty): a
// line for the user each time a fallback is taken (fallback.h: the tiles left go on on the CPU
// when a backend runs out of memory or cannot evaluate the scene's modifiers), also kept in the
// report's notices; called from the workers, one call at a time.
ExportReport exportSceneStreamed(const Scene& scene, const std::string& path,
                                 const ExportOptions& options,
                                 const std::vector<std::shared_ptr<Backend>>& backends,
                                 int workersPerMemory, Progress& progress,
                                 const FallbackNotice& notice = {});
// The same on one backend.
ExportReport exportSceneStreamed(const Scene& scene, const std::string& path,
                                 const ExportOptions& options, std::shared_ptr<Backend> backend,
                                 Progress& progress, const FallbackNotice& notice = {});

}  // namespace strata
