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

#include "engine/ldi/ldi.h"
#include "engine/util/progress.h"

namespace strata {

struct ContourVertex {
  uint64_t key;          // global cell index * 4 + component, or a face vertex key (top bit set)
  glm::dvec3 position;   // global grid units
  double planeDistance;  // grid units: distance to the farthest of its Hermite planes
};

struct ContourTriangle {
  uint64_t vertex[3];  // vertex keys, counter-clockwise seen from outside
  uint64_t order;      // global edge key * 8 + triangle: a tiling-independent order
  uint32_t leaf;       // leaf id of the surfel the edge's crossing came from
};

struct TileContour {
  std::vector<ContourVertex> vertices;  // may repeat vertices of neighbouring tiles (same keys)
  std::vector<ContourTriangle> triangles;
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
// `globalCells` the whole grid's cells (nodes on its outer faces count as outside).
TileContour contourTile(const Ldi& ldi, const glm::ivec3& globalCells, const glm::ivec3& begin,
                        const glm::ivec3& end, Progress* progress);

// Global key of the edge along `axis` whose lower node is `node`.
uint64_t edgeKey(const glm::ivec3& globalCells, int axis, const glm::ivec3& node);

}  // namespace strata
