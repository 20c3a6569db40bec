// The node sides and boundary cells of a tile on the CPU, as bit planes (the contour's first two
// steps; contour_tile.cpp runs the per-cell steps on them). The CUDA twin computes the same
// planes from per-node votes (gpu/contour/contour_tile.cu); both follow decideNodeSide and
// rayVote in contour_cells.h.
//
// The work follows the surface, not the volume: a node's three ray votes are 64 nodes to a word
// (a row's x votes as the prefix parity of its surfels' toggles, y votes as a running row of the
// slab's y toggles, z votes as a running plane of the z toggles bucketed by slice), the majority
// and the unanimity are word operations, and the boundary cells are the mixed bits of a row's
// four node rows. A tile of 1024 cells holds 2 bits a node (286 MB) where bytes per node and
// cell held 3.2 GB, whose first touch by the kernel cost more than the contour itself.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "engine/contour/contour_cells.h"
#include "engine/util/progress.h"

namespace strata {

// The arrays a TileView's node and boundary pointers address (owned here). One TileSides may
// serve tile after tile (contourTile's `reuse`): its planes are kept and grown only when a tile
// needs more, so that later tiles write into pages already touched instead of having the kernel
// zero fresh ones (the planes are a tile's largest arrays: 270 MB at 1024 cells).
struct TileSides {
  std::unique_ptr<uint64_t[]> insideBits;  // rows of TileView::rowWords words, every word written
  std::unique_ptr<uint64_t[]> unanimousBits;
  size_t planeCapacity = 0;        // words each of the planes above holds
  std::vector<uint32_t> boundary;  // boundary cells, increasing window cell index
  std::vector<uint8_t> boundaryMasks;
  uint64_t disagreements = 0;  // window nodes whose three rays disagreed
};

// Decides the sides of the window nodes of `view` (its offsets, surfels, cells, first and
// globalCells set) and finds its boundary cells into *sides, and points view's insideBits,
// unanimousBits, rowWords, boundary, boundaryMasks and boundaryCount at them. Parallel
// (parallelFor); checks `progress` (may be null) between slabs.
void decideTileSides(TileView* view, TileSides* sides, Progress* progress);

}  // namespace strata
