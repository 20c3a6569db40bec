// Dual contouring of one tile of the root's LDI (CPU reference; gpu/contour/contour_tile.cuh is
// its CUDA twin and shares contour_math.h).
//
// A tile owns the grid edges whose lower node lies in [begin, end) (global node indices, per
// axis) and emits one polygon per sign-changing owned edge, joining the vertices of the four
// cells around the edge (a quad, or more where an ambiguous face needs splitting). Vertices are
// keyed globally (cell index * 4 + component), and each is computed from data every tile sees
// identically, so tiles stitch by key into exactly the mesh one big tile gives.
#pragma once

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

#include "engine/contour/contour_cells.h"
#include "engine/contour/tile_sides.h"
#include "engine/ldi/ldi.h"
#include "engine/util/host_array.h"
#include "engine/util/progress.h"

namespace strata {

using ContourVertex = CellVertex;  // see contour_cells.h
using ContourTriangle = CellTriangle;

// Arrays of uninitialised growth (host_array.h): written whole by the contour's workers.
struct TileContour {
  HostArray<ContourVertex> vertices;  // may repeat vertices of neighbouring tiles (same keys)
  HostArray<ContourTriangle> triangles;
  uint64_t synthesizedCrossings = 0;  // edges whose ray had no matching surfel (tangent rays)
  uint64_t signDisagreements = 0;     // nodes whose three rays disagreed (majority decided)
};

// The node window a tile needs: nodes [begin - 1, end] clamped to the grid [0, cells].
struct TileWindow {
  glm::ivec3 first;  // first node of the window
  glm::ivec3 cells;  // cells in the window
};
TileWindow tileWindow(const glm::ivec3& begin, const glm::ivec3& end, const glm::ivec3& cells);

// Contours a tile. `ldi` is the root's LDI sampled on grid.window(window.first, window.cells);
// `globalCells` the whole grid's cells (nodes on its outer faces count as outside). `reuse`
// (may be null): arrays the previous tile left, kept for the next (tile_sides.h); one contour at
// a time uses it.
TileContour contourTile(const Ldi& ldi, const glm::ivec3& globalCells, const glm::ivec3& begin,
                        const glm::ivec3& end, Progress* progress, TileSides* reuse = nullptr);

// The view of a tile's window for the shared per-cell steps, without its arrays.
TileView makeTileView(const glm::ivec3& first, const glm::ivec3& cells,
                      const glm::ivec3& globalCells, const glm::ivec3& begin,
                      const glm::ivec3& end);

}  // namespace strata
