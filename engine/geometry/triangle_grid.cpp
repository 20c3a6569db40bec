#include "engine/geometry/triangle_grid.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "engine/geometry/mesh.h"
#include "engine/geometry/triangle_distance.h"
#include "engine/util/error.h"
#include "engine/util/hash.h"
#include "engine/util/large_array.h"
#include "engine/util/parallel_for.h"

namespace strata {
namespace {

uint64_t cellKey(const glm::ivec3& c) {
  return (uint64_t(uint32_t(c.x) & 0x1fffff) << 42) | (uint64_t(uint32_t(c.y) & 0x1fffff) << 21) |
         uint64_t(uint32_t(c.z) & 0x1fffff);
}

}  // namespace

TriangleGrid::TriangleGrid(const std::vector<glm::dvec3>& positions,
                           const std::vector<std::array<uint32_t, 3>>& triangles, double reach,
                           const Progress* progress)
    : positions_(positions), triangles_(triangles), reach_(reach) {
  const auto check = [progress](size_t k) {
    if (progress && (k & ((size_t(1) << 20) - 1)) == 0) progress->check();
  };
  Bounds bounds;
  double edges = 0.0;  // summed in order: the cell size is the same on any thread count
  for (size_t k = 0; k < triangles.size(); ++k) {
    check(k);
    const auto& t = triangles[k];
    for (uint32_t v : t) bounds.include(positions[v]);
    edges += glm::length(positions[t[1]] - positions[t[0]]);
  }
  cell_ = std::max(edges / double(std::max<size_t>(triangles.size(), 1)), 2.0 * reach);
  if (!(cell_ > 0.0) || !std::isfinite(cell_)) cell_ = 1.0;
  origin_ = bounds.empty() ? glm::dvec3(0.0) : bounds.min - glm::dvec3(reach + cell_);
  spheres_.resize(triangles.size());
  // The (cell, triangle) pairs, made in parallel by blocks of triangles and scattered into
  // buckets by the cell's hash (in block order), each bucket then sorted on its own: the same
  // order as one sort of all pairs by (cell, triangle) within each bucket, on any thread count.
  constexpr int kBucketBits = 8;
  constexpr size_t kBuckets = size_t(1) << kBucketBits;
  auto bucketOf = [](uint64_t key) { return size_t(avalanche64(key) >> (64 - kBucketBits)); };
  const int64_t count = int64_t(triangles.size());
  constexpr int64_t kBlock = 1 << 14;
  const int64_t blocks = (count + kBlock - 1) / kBlock;
  std::vector<std::vector<std::pair<uint64_t, uint32_t>>> perBlock(static_cast<size_t>(blocks));
  parallelFor(0, blocks, 1, [&](int64_t first, int64_t last) {
    for (int64_t block = first; block < last; ++block) {
      if (progress) progress->check();
      auto& pairs = perBlock[size_t(block)];
      const int64_t end = std::min(count, (block + 1) * kBlock);
      for (int64_t i = block * kBlock; i < end; ++i) {
        const uint32_t t = uint32_t(i);
        Bounds box;
        for (uint32_t v : triangles[t]) box.include(positions[v]);
        spheres_[t] = glm::dvec4(box.center(), 0.5 * glm::length(box.size()));
        const glm::ivec3 lo = cellOf(box.min - glm::dvec3(reach));
        const glm::ivec3 hi = cellOf(box.max + glm::dvec3(reach));
        // Only the cells the triangle's plane passes within reach of: a large tilted triangle
        // (a simplified mesh has some) would otherwise fill the cube of its box.
        const glm::dvec3 a = positions[triangles[t][0]];
        glm::dvec3 normal =
            glm::cross(positions[triangles[t][1]] - a, positions[triangles[t][2]] - a);
        const double length = glm::length(normal);
        const bool planar = length > 0.0 && std::isfinite(length);
        if (planar) normal /= length;
        const double slab = reach + 0.5 * std::sqrt(3.0) * cell_;  // plane to a cell's centre
        for (int z = lo.z; z <= hi.z; ++z)
          for (int y = lo.y; y <= hi.y; ++y)
            for (int x = lo.x; x <= hi.x; ++x) {
              const glm::dvec3 centre = origin_ + (glm::dvec3(x, y, z) + 0.5) * cell_;
              if (planar && std::abs(glm::dot(centre - a, normal)) > slab) continue;
              pairs.emplace_back(cellKey({x, y, z}), t);
            }
      }
    }
  });
  // Bucket sizes and each block's place in each bucket.
  std::vector<size_t> start(kBuckets * size_t(blocks) + 1, 0);  // [bucket][block]
  parallelFor(0, blocks, 1, [&](int64_t first, int64_t last) {
    for (int64_t block = first; block < last; ++block)
      for (const auto& pair : perBlock[size_t(block)])
        ++start[bucketOf(pair.first) * size_t(blocks) + size_t(block) + 1];
  });
  for (size_t k = 1; k < start.size(); ++k) start[k] += start[k - 1];
  const size_t total = start.back();
  if (total >= size_t(UINT32_MAX))
    throw Error("a triangle grid of " + std::to_string(total) +
                " cell entries is beyond its 32-bit index");
  // Uninitialised, filled by the scatter on every thread (a std::vector's zeroing of hundreds of
  // MB on one thread took 2 s of a 4 M-triangle export's simplification, and no cancel could
  // reach it).
  struct CellEntry {
    uint64_t key;
    uint32_t triangle;
    bool operator<(const CellEntry& o) const {
      return key != o.key ? key < o.key : triangle < o.triangle;
    }
  };
  LargeArray<CellEntry> pairs(total);
  parallelFor(0, blocks, 1, [&](int64_t first, int64_t last) {
    for (int64_t block = first; block < last; ++block) {
      std::vector<size_t> at(kBuckets);
      if (progress) progress->check();
      for (size_t b = 0; b < kBuckets; ++b) at[b] = start[b * size_t(blocks) + size_t(block)];
      for (const auto& pair : perBlock[size_t(block)])
        pairs[at[bucketOf(pair.first)]++] = CellEntry{pair.first, pair.second};
      perBlock[size_t(block)] = {};
    }
  });
  parallelFor(0, int64_t(kBuckets), 1, [&](int64_t first, int64_t last) {
    for (int64_t b = first; b < last; ++b) {
      if (progress) progress->check();
      std::sort(pairs.get() + start[size_t(b) * size_t(blocks)],
                pairs.get() + start[size_t(b + 1) * size_t(blocks)]);
    }
  });
  items_.resize(pairs.size());
  size_t cells = 0;
  if (progress) progress->check();
  for (size_t k = 0; k < pairs.size(); ++k) {
    check(k);
    items_[k] = pairs[k].triangle;
    if (k == 0 || pairs[k].key != pairs[k - 1].key) ++cells;
  }
  size_t slots = 16;
  while (slots < 2 * cells) slots *= 2;
  table_.assign(slots, Slot{});
  for (size_t k = 0, checked = 0; k < pairs.size();) {
    if (progress && k - checked >= (size_t(1) << 20)) {
      progress->check();
      checked = k;
    }
    size_t end = k;
    while (end < pairs.size() && pairs[end].key == pairs[k].key) ++end;
    size_t slot = avalanche64(pairs[k].key) & (slots - 1);
    while (table_[slot].end != 0) slot = (slot + 1) & (slots - 1);
    table_[slot] = {pairs[k].key, uint32_t(k), uint32_t(end)};
    k = end;
  }
}

glm::ivec3 TriangleGrid::cellOf(const glm::dvec3& p) const {
  // Clamped before the conversion (a far or non-finite point lands in an outer cell, which
  // holds no triangle or only ones the exact test then rejects).
  glm::ivec3 c;
  for (int axis = 0; axis < 3; ++axis) {
    const double v = std::floor((p[axis] - origin_[axis]) / cell_);
    c[axis] = v >= -1e9 && v <= 1e9 ? int(v) : (v > 0.0 ? int(1e9) : int(-1e9));
  }
  return c;
}

const TriangleGrid::Slot* TriangleGrid::cell(const glm::dvec3& p) const {
  return cellAt(cellOf(p));
}

const TriangleGrid::Slot* TriangleGrid::cellAt(const glm::ivec3& c) const {
  const uint64_t key = cellKey(c);
  const size_t mask = table_.size() - 1;
  for (size_t slot = avalanche64(key) & mask; table_[slot].end != 0; slot = (slot + 1) & mask)
    if (table_[slot].key == key) return &table_[slot];
  return nullptr;
}

bool TriangleGrid::within(const glm::dvec3& p, double distance, uint32_t* hint) const {
  const double distance2 = distance * distance;
  if (hint && *hint < triangles_.size()) {
    const auto& t = triangles_[*hint];
    if (pointTriangleDistanceSquared(p, positions_[t[0]], positions_[t[1]], positions_[t[2]]) <=
        distance2)
      return true;
  }
  const Slot* s = cell(p);
  if (!s) return false;
  for (uint32_t i = s->begin; i < s->end; ++i) {
    const glm::dvec4& sphere = spheres_[items_[i]];
    const glm::dvec3 d = p - glm::dvec3(sphere);
    // Beyond its box's sphere grown by the distance (a hair more, for rounding): not within.
    const double grown = (sphere.w + distance) * (1.0 + 1e-9);
    if (glm::dot(d, d) > grown * grown) continue;
    const auto& t = triangles_[items_[i]];
    if (pointTriangleDistanceSquared(p, positions_[t[0]], positions_[t[1]], positions_[t[2]]) <=
        distance2) {
      if (hint) *hint = items_[i];
      return true;
    }
  }
  return false;
}

double TriangleGrid::nearest(const glm::dvec3& p, uint32_t* index) const {
  const Slot* s = cell(p);
  double best = reach_ * reach_;
  // Beyond its box's sphere grown by the best distance so far (a hair more, on the whole grown
  // radius: never passes over a triangle whose exact distance would have been nearer): not
  // measured.
  double bestDistance = reach_;
  uint32_t which = UINT32_MAX;
  if (s)
    for (uint32_t i = s->begin; i < s->end; ++i) {
      const glm::dvec4& sphere = spheres_[items_[i]];
      const glm::dvec3 d = p - glm::dvec3(sphere);
      const double grown = (sphere.w + bestDistance) * (1.0 + 1e-9);
      if (glm::dot(d, d) > grown * grown) continue;
      const auto& t = triangles_[items_[i]];
      const double d2 =
          pointTriangleDistanceSquared(p, positions_[t[0]], positions_[t[1]], positions_[t[2]]);
      if (d2 < best) {  // the first of equals (a fixed order): deterministic
        best = d2;
        bestDistance = std::sqrt(best);
        which = items_[i];
      }
    }
  if (index) *index = which;
  return std::sqrt(best);
}

double TriangleGrid::distanceTo(const glm::dvec3& p, uint32_t t) const {
  const auto& tri = triangles_[t];
  return std::sqrt(
      pointTriangleDistanceSquared(p, positions_[tri[0]], positions_[tri[1]], positions_[tri[2]]));
}

}  // namespace strata
