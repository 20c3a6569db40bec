// Triangles of a mesh bucketed by the cells of a uniform grid, for "how far is this point from
// the surface, up to `reach`" queries in about constant time: each triangle is listed in every
// cell that its box, grown by `reach`, overlaps and its plane passes within reach of; cells are
// found through an open-addressing table. Cells are about a triangle across (the mean edge) and
// at least 2 * reach. Coordinates must be finite; throws strata::Error beyond 2^32 entries.
//
// Threads: immutable after construction; queries may run on any number of threads at once. The
// mesh's arrays must outlive the grid (they are referenced, not copied).
#pragma once

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace strata {

class TriangleGrid {
 public:
  TriangleGrid(const std::vector<glm::dvec3>& positions,
               const std::vector<std::array<uint32_t, 3>>& triangles, double reach);

  // True when some triangle lies within `distance` (<= reach) of p.
  bool within(const glm::dvec3& p, double distance) const;
  // The distance from p to the nearest triangle, or `reach` when none is nearer; `index`, when
  // given, receives that triangle's index (UINT32_MAX when none is within reach).
  double nearest(const glm::dvec3& p, uint32_t* index = nullptr) const;
  // The distance from p to triangle `t` (any triangle of the mesh, however far).
  double distanceTo(const glm::dvec3& p, uint32_t t) const;
  double reach() const { return reach_; }

 private:
  struct Slot {
    uint64_t key = 0;
    uint32_t begin = 0, end = 0;  // items_[begin, end); end == 0: an empty slot
  };
  const Slot* cell(const glm::dvec3& p) const;
  glm::ivec3 cellOf(const glm::dvec3& p) const;

  const std::vector<glm::dvec3>& positions_;
  const std::vector<std::array<uint32_t, 3>>& triangles_;
  double reach_;
  double cell_ = 1.0;
  glm::dvec3 origin_{0.0};
  std::vector<glm::dvec4> spheres_;  // per triangle: its box's centre, (half diagonal + reach)^2
  std::vector<uint32_t> items_;
  std::vector<Slot> table_;
};

}  // namespace strata
