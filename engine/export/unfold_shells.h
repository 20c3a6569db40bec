// Shells that vertex placement turned inside out, put right.
//
// Dual contouring joins the vertices of the cells around each sign-changing grid edge, so a
// shell's orientation comes from the grid: it encloses its inside nodes (an outer shell, positive
// volume) or a void (negative volume). Each vertex is then moved to its cell's QEF minimiser.
// Where a part is thinner than a cell, the minimisers of all the cells around it crowd onto the
// thin surface and can fold the shell through itself until its signed volume has the wrong
// sign: a closed, manifold mesh that a slicer reads as a void where there is material.
//
// Measured against the same shell with every cell vertex at its cell's centre (the boundary of
// the union of the inside nodes' dual cubes, whose orientation is the grid's own), a shell whose
// volume has a different sign, or none, is pulled towards those centres by halves (1/2, 1/4,
// ... of the way back from the centres) until the signs agree, and at worst to the centres.
// Vertices of cells with several components are pulled halfway between centre and their own
// position instead, so that they stay apart.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/contour/contour_tile.h"
#include "engine/geometry/mesh.h"
#include "engine/ldi/grid.h"

namespace strata {

// `mesh` is the indexed contour in scene units on `grid` (the whole grid, not a tile's window);
// `keys` the keys of the contour vertices it was built from (same order: vertex i has key
// keys[i]); `rootOf` its vertices' component roots (vertexComponentRoots). Moves the
// vertices of inverted shells; returns how many shells it moved.
int unfoldInvertedShells(const Grid& grid, const std::vector<uint64_t>& keys,
                         const std::vector<uint32_t>& rootOf, TriangleMesh* mesh);

}  // namespace strata
