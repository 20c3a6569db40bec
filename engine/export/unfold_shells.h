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

#include <array>
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

// The steps above, shared with the streamed export (streamed_export.h), which runs them on a
// mesh it holds a piece at a time.
//
// Whether vertex i of keys sorted in key order shares its cell with another component's vertex
// (their keys are adjacent: cell * 4 + component).
inline bool sharesCell(const std::vector<uint64_t>& keys, size_t i) {
  const uint64_t cell = keys[i] / 4;
  return (i > 0 && keys[i - 1] / 4 == cell) || (i + 1 < keys.size() && keys[i + 1] / 4 == cell);
}
// Where the vertex with `key` at `position` goes at the grid's own placement: its cell's
// centre, or halfway there when `sharedCell`; a face-segment vertex stays.
glm::dvec3 shellAnchor(const Grid& grid, uint64_t key, bool sharedCell, const glm::dvec3& position);
// Six times the signed volume of one triangle, corners relative to a reference point.
double sixVolumeTerm(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);
int volumeSign(double x);
// How much of each vertex's offset from its anchor an inverted shell keeps (1/2, 1/4, ...,
// 1/32, else 0): the first at which the shell's six volume (its triangles in order, corners
// indexing anchors and positions, relative to `ref`) has the sign `want`.
double pullBackKeep(const std::vector<std::array<uint32_t, 3>>& triangles,
                    const std::vector<glm::dvec3>& anchors,
                    const std::vector<glm::dvec3>& positions, const glm::dvec3& ref, int want);

}  // namespace strata
