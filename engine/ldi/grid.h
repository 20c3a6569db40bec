// The sampling grid: a cubic lattice of nodes at origin + h * (i, j, k), seen through a window.
//
// The lattice (origin, h) is global; a Grid covers the window of `cells` cells starting at the
// global node `first` (zero for a whole grid, the tile's first node for a tile). For each axis a
// there is one ray per node line along a: the rays of axis a are indexed by the window's node
// coordinates (i, j) on the two other axes u = (a+1)%3, v = (a+2)%3 (a right-handed (u, v, a)
// frame), ray index = i + j * (cells[u] + 1), and lie on the global node line
// (first[u] + i, first[v] + j). Depths along a ray are in global grid units (cells from the
// global origin): the world point of depth t on that ray has coordinate origin[a] + h * t on
// axis a. Because every coordinate is global, a tile computes exactly what the whole grid
// computes on the same rays.
#pragma once

#include <glm/vec3.hpp>

#include <cstdint>

#include "engine/geometry/mesh.h"
#include "engine/ldi/shared_math.h"
#include "engine/util/limits.h"

namespace strata {

struct Grid {
  glm::dvec3 origin{0.0};
  double h = 1.0;             // cell size in scene units
  glm::ivec3 cells{1, 1, 1};  // cells per axis; nodes per axis = cells + 1
  glm::ivec3 first{0, 0, 0};  // global index of the window's first node

  int uAxis(int axis) const { return (axis + 1) % 3; }
  int vAxis(int axis) const { return (axis + 2) % 3; }
  int raysU(int axis) const { return cells[uAxis(axis)] + 1; }
  int raysV(int axis) const { return cells[vAxis(axis)] + 1; }
  int64_t rayCount(int axis) const { return int64_t(raysU(axis)) * raysV(axis); }
  int64_t nodeCount() const { return int64_t(cells.x + 1) * (cells.y + 1) * (cells.z + 1); }
  Bounds bounds() const;
  bool operator==(const Grid& o) const {
    return origin == o.origin && h == o.h && cells == o.cells && first == o.first;
  }
  // The window of `count` cells starting at global node `start` on the same lattice.
  Grid window(const glm::ivec3& start, const glm::ivec3& count) const {
    Grid g = *this;
    g.first = start;
    g.cells = count;
    return g;
  }
};

// Number of guard cells kept between the scene bounds and each side of an automatic grid, so
// that surfaces never touch the grid's boundary.
constexpr int kGuardCells = 2;

// A grid over `bounds` grown by `margin` (fraction of the largest extent) with `resolution`
// cells along the longest side, guard cells included. Throws strata::Error for resolution < 8
// or > kMaxResolution, or for empty / non-finite bounds.
Grid makeGrid(const Bounds& bounds, int resolution, double margin);

// A grid covering exactly `box` (origin at box.min) with `resolution` cells along the longest
// side; the other sides get ceil(extent / h) cells. Used for explicit bounds in scene files.
Grid makeGridExact(const Bounds& box, int resolution);

}  // namespace strata
