// Triangles of a mesh bucketed by the cells of a uniform grid, for "how far is this point from
// the surface, up to `reach`" queries in about constant time: each triangle is listed in every
// cell that its box, grown by `reach`, overlaps and its plane passes within reach of; cells are
// found through an open-addressing table. Cells are about a triangle across (the mean edge) and
// at least 2 * reach. Coordinates must be finite; throws strata::Error beyond 2^32 entries.
//
// Threads: immutable after construction; queries may run on any number of threads at once. The
// mesh's arrays must outlive the grid (they are referenced, not copied).
#pragma once

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "engine/util/progress.h"

namespace strata {

class TriangleGrid {
 public:
  // `progress` (may be null) is checked as it is built, every million or so entries: a grid of
  // tens of millions of triangles takes seconds, and a cancel must not wait for it (throws
  // Cancelled).
  TriangleGrid(const std::vector<glm::dvec3>& positions,
               const std::vector<std::array<uint32_t, 3>>& triangles, double reach,
               const Progress* progress = nullptr);

  // True when some triangle lies within `distance` (<= reach) of p. `hint` (may be null): a
  // triangle to try first (any value; UINT32_MAX for none), set to the one found within: a run
  // of nearby queries mostly finds the last one's triangle again, without the cell's list.
  bool within(const glm::dvec3& p, double distance, uint32_t* hint = nullptr) const;
  // The distance from p to the nearest triangle, or `reach` when none is nearer; `index`, when
  // given, receives that triangle's index (UINT32_MAX when none is within reach).
  double nearest(const glm::dvec3& p, uint32_t* index = nullptr) const;
  // The distance from p to triangle `t` (any triangle of the mesh, however far).
  double distanceTo(const glm::dvec3& p, uint32_t t) const;
  double reach() const { return reach_; }
  double cellSize() const { return cell_; }
  const glm::dvec3& corner(uint32_t t, int k) const { return positions_[triangles_[t][k]]; }

  // Calls visit(t) for each triangle listed in a cell that triangle (a, b, c) passes through
  // (a superset of the triangles within `reach` of it; some more than once), while visit
  // returns true. False when visit stopped it or the triangle spans more than `cellLimit` cells
  // of its box (nothing visited then).
  template <class Visit>
  bool visitNear(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, long cellLimit,
                 Visit&& visit) const;

 private:
  struct Slot {
    uint64_t key = 0;
    uint32_t begin = 0, end = 0;  // items_[begin, end); end == 0: an empty slot
  };
  const Slot* cell(const glm::dvec3& p) const;
  const Slot* cellAt(const glm::ivec3& c) const;
  glm::ivec3 cellOf(const glm::dvec3& p) const;

  const std::vector<glm::dvec3>& positions_;
  const std::vector<std::array<uint32_t, 3>>& triangles_;
  double reach_;
  double cell_ = 1.0;
  glm::dvec3 origin_{0.0};
  std::vector<glm::dvec4> spheres_;  // per triangle: its box's centre and half diagonal
  std::vector<uint32_t> items_;
  std::vector<Slot> table_;
};

template <class Visit>
bool TriangleGrid::visitNear(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                             long cellLimit, Visit&& visit) const {
  const glm::dvec3 lo = glm::min(a, glm::min(b, c)), hi = glm::max(a, glm::max(b, c));
  const glm::ivec3 first = cellOf(lo), last = cellOf(hi);
  const glm::dvec3 span = glm::dvec3(last - first) + 1.0;
  if (!(span.x * span.y * span.z <= double(cellLimit))) return false;
  glm::dvec3 normal = glm::cross(b - a, c - a);
  const double length = std::sqrt(normal.x * normal.x + normal.y * normal.y + normal.z * normal.z);
  const bool planar = length > 0.0 && std::isfinite(length);
  if (planar) normal /= length;
  const double halfDiagonal = 0.5 * std::sqrt(3.0) * cell_;
  for (int z = first.z; z <= last.z; ++z)
    for (int y = first.y; y <= last.y; ++y)
      for (int x = first.x; x <= last.x; ++x) {
        const glm::dvec3 centre = origin_ + (glm::dvec3(x, y, z) + 0.5) * cell_;
        if (planar) {
          const glm::dvec3 d = centre - a;
          if (std::abs(d.x * normal.x + d.y * normal.y + d.z * normal.z) > halfDiagonal) continue;
        }
        const Slot* s = cellAt({x, y, z});
        if (!s) continue;
        for (uint32_t i = s->begin; i < s->end; ++i)
          if (!visit(items_[i])) return false;
      }
  return true;
}

}  // namespace strata
