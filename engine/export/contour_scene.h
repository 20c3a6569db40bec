// Watertight export: the scene's root surface as a closed, oriented 2-manifold triangle mesh,
// by dual contouring on the LDI, tile by tile.
//
// Each tile of `tileCells`^3 cells is evaluated on its own window of the grid (rays clipped to
// the tile plus a one-cell halo), contoured, and stitched by global vertex keys; the result is
// identical to contouring the whole grid at once, while the LDI memory follows the tile.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "engine/contour/contour_tile.h"
#include "engine/document/scene.h"
#include "engine/eval/evaluator.h"
#include "engine/export/drop_specks.h"
#include "engine/geometry/export_mesh.h"
#include "engine/ldi/offset_math.h"
#include "engine/util/error.h"
#include "engine/util/progress.h"

namespace strata {

struct ContourOptions {
  int resolution = 0;  // cells along the longest side; 0 = the scene's setting
  int tileCells = 0;   // tile edge in cells (>= 8; 0 = exportTileCells below); tiles of the
                       // whole grid are one tile
};

// The largest tile edge: a tile's window of cells is indexed in 32 bits (contour_cells.h).
constexpr int kMaxTileCells = 1024;
// Device or host bytes per window node that contouring a tile holds at once, for sizing tiles:
// the CUDA backend's byte of votes or of cell flags beside the two bit planes of node sides
// (the CPU backend holds the bit planes only: tile_sides.h), rounded up.
constexpr uint64_t kContourBytesPerNode = 2;

// The tile edge an export uses when none is given: the longest side of `grid` split into the
// fewest equal parts whose tiles are at most kMaxTileCells and whose contouring arrays take at
// most a quarter of `memoryBytes` (the backend's memoryAvailable(); the rest is for the tile's
// LDIs and the mesh). Fewer tiles evaluate the tree fewer times. 0 bytes (unknown): 256.
// With modifiers (`halo` > 0: modifierHaloCells) each tile is evaluated on its window grown by
// `halo` cells a side, and the offsets' arrays of that window (`offsetBytesPerNode`: the
// backend's Backend::offsetBytesPerNode) are what must fit; its cells are also kept within
// 2^32. 0 when no tile fits that (a halo of hundreds of cells).
int exportTileCells(const Grid& grid, uint64_t memoryBytes, int halo = 0,
                    uint64_t offsetBytesPerNode = kOffsetBytesPerNode);
// Cells along each axis of the window a tile of `tileCells` is evaluated on: the tile and `halo`
// cells on both sides, within the grid (the contour's own cell of halo and the nodes not
// counted).
glm::dvec3 grownTileCells(const Grid& grid, int tileCells, int halo);
glm::dvec3 grownTileCells(const Grid& grid, const glm::ivec3& size, int halo);

struct ContourReport {
  Grid grid;
  int tiles = 0;
  int tileCells = 0;             // the tile edge used
  double evaluateSeconds = 0.0;  // sampling and Booleans, all tiles
  double contourSeconds = 0.0;   // signs, vertices, quads, all tiles
  double mergeSeconds = 0.0;     // stitching and indexing
  // Of mergeSeconds, its steps where they are timed apart (the streamed export's slabs and
  // passes: streamed_export.h), in order.
  std::vector<std::pair<std::string, double>> mergeSteps;
  uint64_t peakBytes = 0;     // process peak resident memory afterwards
  uint64_t surfels = 0;       // root surfels over all tiles
  uint64_t tileLdiBytes = 0;  // the most LDI memory one tile's evaluation held (its cache)
  // Of evaluateSeconds, the modifiers' (EvalResult::modifySeconds), and the nodes of the grid
  // windows of the tiles they ran in: the estimate scales that time with nodes, not surface.
  double modifySeconds = 0.0;
  double modifiedNodes = 0.0;
  uint64_t synthesizedCrossings = 0;
  uint64_t signDisagreements = 0;
  // Every vertex lies in a cell the surface crosses: the distance from any output vertex to
  // the sampled surface is at most the cell diagonal, sqrt(3) h (scene units).
  double deviationBound = 0.0;
  // Measured: the largest distance of a vertex from the tangent planes of its own Hermite data
  // (scene units); small where the QEF could fit the planes (flat parts, sharp features).
  double maxPlaneDistance = 0.0;
  // Shells that vertex placement had turned inside out (a part thinner than a cell), pulled
  // back towards their cells' centres (unfold_shells.h).
  int unfoldedShells = 0;
  // Closed components the grid does not resolve, left out (drop_specks.h).
  DroppedSpecks droppedSpecks;
  // Said once each over all tiles: parts smaller than a cell, ... (EvalResult::warnings).
  std::vector<std::string> warnings;
};

// The error of an export whose result has no triangles, for the file it would have written:
// "the result is empty, so nothing was written to PATH", and why where the evaluation said
// (r.warnings: a part shrunk away, parts smaller than a cell), else the usual causes.
Error emptyResultError(const std::string& path, const ContourReport& r);
// Adds the warnings of `from` not yet in into->warnings (each said once over all tiles).
void addWarnings(const std::vector<std::string>& from, ContourReport* into);
// Adds the surfel, crossing and sign counts and the warnings of tiles contoured apart (by
// another worker or process) to *into; times are the caller's to combine.
void addTileCounts(const ContourReport& from, ContourReport* into);

// Contours the visible tree. Throws strata::Error or Cancelled; progress stage "export".
ExportMesh contourScene(const Scene& scene, Evaluator& evaluator, const ContourOptions& options,
                        Progress& progress, ContourReport* report = nullptr);

// contourScene in its three steps, for exports whose tiles are contoured by several processes
// (distributed_export.h): the tiling, the tiles a process contours, and the mesh from all of
// them. Tiles are keyed on the global lattice, so tiles contoured anywhere merge into the mesh
// one process makes, vertex for vertex.
struct ExportTiling {
  Grid grid;             // the whole export's grid
  int tileCells = 0;     // tile edge in cells (of a slab tiling: its slabs' depth along z)
  glm::ivec3 size{0};    // cells of a tile per axis: tileCells each, or a slab's (whole x and y)
  glm::ivec3 counts{0};  // tiles per axis
  int halo = 0;          // cells evaluated around each tile's window (modifierHaloCells)
  int count() const;
  // Tile t's owned cells [begin, end): tiles numbered x fastest, then y, then z.
  glm::ivec3 begin(int tile) const;
  glm::ivec3 end(int tile) const;
  // The nodes every tile's evaluation samples, summed (evaluationWindow): the work a tiling
  // costs beyond the grid's own nodes, in the halos its tiles share.
  double evaluatedNodes() const;
};
// The cells tile [begin, end) of `grid` is evaluated on: its window (tileWindow: its cells and
// a cell of its neighbours') grown by `halo` cells on every side, within the grid; [first, end).
struct EvaluationWindow {
  glm::ivec3 first{0}, end{0};
};
EvaluationWindow evaluationWindow(const Grid& grid, int halo, const glm::ivec3& begin,
                                  const glm::ivec3& end);
// The tiling of an export with `options` on a backend with `memoryBytes` free whose offsets
// hold `offsetBytesPerNode` (exportTileCells).
// A scene with modifiers is tiled too: each tile is evaluated on its window grown by the
// modifiers' halo and then cropped to it (Backend::crop), so that it holds what the whole grid
// holds there. Throws strata::Error when no tile fits.
ExportTiling exportTiling(const Scene& scene, const ContourOptions& options, uint64_t memoryBytes,
                          uint64_t offsetBytesPerNode);
// The tiling of the export with tiles of `size` cells per axis (another process's choice,
// distributed_export.h; a slab tiling, streamed_export.h). Throws strata::Error where a tile's
// window (grown by the modifiers' halo) would hold more than 2^32 cells.
ExportTiling exportTilingOfSize(const Scene& scene, const ContourOptions& options,
                                const glm::ivec3& size);

// Evaluates and contours the tiles t of `tiling` with mine(t) (all when `mine` is empty) in
// increasing order, appending them to *out and adding to r (grid, tiles, times, counts);
// progress "export" over those tiles, or afterTile(t) after each when set (which then reports).
// mine(t) is asked once per tile, just before it would be contoured, when afterTile is set (so
// it may claim the tile from a shared queue); without afterTile it is also asked up front.
void contourTiles(const Scene& scene, Evaluator& evaluator, const ExportTiling& tiling,
                  const std::function<bool(int)>& mine, Progress& progress, ContourReport& r,
                  std::vector<TileContour>* out, const std::function<void(int)>& afterTile = {});

// Contoured tiles (any subset, in any order: each tile once) merged into one indexed mesh in
// scene units on r.grid, before the component steps: vertices one per key in key order (keys[i]
// is vertex i's), triangles in edge order, each with its leaf and CellTriangle::resolved bits.
// The tiles' vertices include those of their windows' halo cells, so a subset of tiles gives
// every vertex its triangles use (and some no triangle uses). Adds to r.maxPlaneDistance.
struct MergedTiles {
  ExportMesh mesh;
  std::vector<uint64_t> keys;
  std::vector<uint8_t> resolved;
};
// *sortSeconds (where given): the time spent putting each tile's arrays in order.
MergedTiles mergeTiles(const Scene& scene, std::vector<TileContour> tiles, Progress& progress,
                       ContourReport& r, double* sortSeconds = nullptr);

// The mesh from contoured tiles (any subset, in any order: each tile once): merged, indexed,
// shells unfolded, specks dropped. Sets r's merge time, deviation bound and peak memory.
ExportMesh meshFromTiles(const Scene& scene, std::vector<TileContour> tiles, Progress& progress,
                         ContourReport& r);

}  // namespace strata
