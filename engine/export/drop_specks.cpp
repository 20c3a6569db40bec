#include "engine/export/drop_specks.h"

#include <glm/common.hpp>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstring>
#include <limits>
#include <unordered_map>

#include "engine/contour/contour_cells.h"
#include "engine/geometry/mesh_components.h"
#include "engine/util/parallel_for.h"

namespace strata {
namespace {

constexpr uint32_t kMeasuredVertices = kMeasuredSpeckVertices;

struct Box {
  glm::dvec3 lo{std::numeric_limits<double>::infinity()};
  glm::dvec3 hi{-std::numeric_limits<double>::infinity()};
};

// Keeps the elements i < count for which keep(i) holds, in order, at the front: move(from, to,
// count) moves `count` elements from index `from` to index `to` (to <= from; the ranges may
// overlap: memmove). The tests run in parallel over fixed blocks, each block's kept runs moved
// to the block's front; the blocks are then moved to their places one after the other (a
// block's destination may hold an earlier block's elements until that one has moved). Returns
// how many were kept.
template <typename Keep, typename Move>
size_t compactInOrder(size_t count, Keep keep, Move move) {
  constexpr size_t kBlock = 65536;
  const size_t blocks = (count + kBlock - 1) / kBlock;
  std::vector<size_t> kept(blocks, 0);
  parallelFor(0, int64_t(blocks), 1, [&](int64_t b, int64_t e) {
    for (int64_t k = b; k < e; ++k) {
      const size_t first = size_t(k) * kBlock, last = std::min(count, first + kBlock);
      size_t to = first;
      for (size_t i = first; i < last;) {
        if (!keep(i)) {
          ++i;
          continue;
        }
        size_t end = i + 1;
        while (end < last && keep(end)) ++end;
        if (to != i) move(i, to, end - i);
        to += end - i;
        i = end;
      }
      kept[size_t(k)] = to - first;
    }
  });
  size_t to = 0;
  for (size_t k = 0; k < blocks; ++k) {
    if (to != k * kBlock && kept[k] > 0) move(k * kBlock, to, kept[k]);
    to += kept[k];
  }
  return to;
}

}  // namespace

std::string droppedSpecksSentence(const DroppedSpecks& dropped) {
  if (dropped.components == 0) return "";
  char text[200];
  std::snprintf(text, sizeof(text),
                "%d speck%s the grid cannot resolve left out (%zu triangles: closed components "
                "within one cell, or around nodes the rays disagree on)",
                dropped.components, dropped.components == 1 ? "" : "s", dropped.triangles);
  return text;
}

bool keepComponent(uint8_t bits, uint32_t vertices, const glm::dvec3& lo, const glm::dvec3& hi,
                   double cell) {
  constexpr uint8_t kBoth = kInsideResolved | kOutsideResolved;
  if ((bits & kBoth) != kBoth) return false;
  if (vertices > kMeasuredSpeckVertices) return true;
  const glm::dvec3 side = hi - lo;
  return side.x >= cell || side.y >= cell || side.z >= cell;
}

DroppedSpecks dropUnresolvedSpecks(ExportMesh* mesh, std::vector<uint8_t>* resolved, double cell,
                                   const std::vector<uint32_t>* roots) {
  DroppedSpecks dropped;
  auto& triangles = mesh->mesh.triangles;
  auto& positions = mesh->mesh.positions;
  const size_t n = positions.size();
  if (triangles.empty() || resolved->size() != triangles.size()) return dropped;
  // Components over vertices; per root: the resolved bits (OR over its triangles) and the
  // vertex count.
  std::vector<uint32_t> computed;
  if (!roots || roots->size() != n) {
    computed = vertexComponentRoots(mesh->mesh);
    roots = &computed;
  }
  const std::vector<uint32_t>& rootOf = *roots;
  std::vector<std::atomic<uint8_t>> bits(n);
  std::vector<std::atomic<uint32_t>> count(n);
  parallelFor(0, int64_t(n), 65536, [&](int64_t b, int64_t e) {
    for (int64_t v = b; v < e; ++v) {
      bits[size_t(v)].store(0, std::memory_order_relaxed);
      count[size_t(v)].store(0, std::memory_order_relaxed);
    }
  });
  constexpr uint8_t kHasTriangle = 4;
  // Accumulated per run of one root and added once per run: neighbouring triangles and vertices
  // mostly share a component, and one atomic per element on one component's counter serialises
  // every thread on its cache line (most of the merge's time on a 16-core host).
  parallelFor(0, int64_t(triangles.size()), 65536, [&](int64_t b, int64_t e) {
    uint32_t run = UINT32_MAX;
    uint8_t runBits = 0;
    for (int64_t t = b; t < e; ++t) {
      const uint32_t root = rootOf[triangles[size_t(t)][0]];
      if (root != run) {
        if (run != UINT32_MAX) bits[run].fetch_or(runBits, std::memory_order_relaxed);
        run = root;
        runBits = 0;
      }
      runBits |= uint8_t((*resolved)[size_t(t)] | kHasTriangle);
    }
    if (run != UINT32_MAX) bits[run].fetch_or(runBits, std::memory_order_relaxed);
  });
  parallelFor(0, int64_t(n), 65536, [&](int64_t b, int64_t e) {
    uint32_t run = UINT32_MAX, runCount = 0;
    for (int64_t v = b; v < e; ++v) {
      const uint32_t root = rootOf[size_t(v)];
      if (root != run) {
        if (run != UINT32_MAX) count[run].fetch_add(runCount, std::memory_order_relaxed);
        run = root;
        runCount = 0;
      }
      ++runCount;
    }
    if (run != UINT32_MAX) count[run].fetch_add(runCount, std::memory_order_relaxed);
  });
  // The boxes of the small components: gathered per chunk of vertices, then joined.
  constexpr size_t kChunk = size_t(1) << 18;
  const size_t chunks = (n + kChunk - 1) / kChunk;
  std::vector<std::unordered_map<uint32_t, Box>> chunkBoxes(chunks);
  parallelFor(0, int64_t(chunks), 1, [&](int64_t b, int64_t e) {
    for (int64_t chunk = b; chunk < e; ++chunk)
      for (size_t v = size_t(chunk) * kChunk; v < std::min(n, size_t(chunk + 1) * kChunk); ++v) {
        const uint32_t root = rootOf[v];
        if (count[root].load(std::memory_order_relaxed) > kMeasuredVertices) continue;
        Box& box = chunkBoxes[size_t(chunk)][root];
        box.lo = glm::min(box.lo, positions[v]);
        box.hi = glm::max(box.hi, positions[v]);
      }
  });
  std::unordered_map<uint32_t, Box> boxes;
  for (const auto& chunk : chunkBoxes)
    for (const auto& [root, part] : chunk) {
      Box& box = boxes[root];
      box.lo = glm::min(box.lo, part.lo);
      box.hi = glm::max(box.hi, part.hi);
    }
  chunkBoxes.clear();
  // Which roots stay.
  std::vector<uint8_t> keepRoot(n);
  std::atomic<int> droppedComponents{0};
  parallelFor(0, int64_t(n), int64_t(kChunk), [&](int64_t first, int64_t last) {
    int localDropped = 0;
    for (size_t v = size_t(first); v < size_t(last); ++v) {
      keepRoot[v] = 0;
      if (rootOf[v] != v) continue;
      const uint8_t b = bits[v].load(std::memory_order_relaxed);
      if (!(b & kHasTriangle)) continue;  // a vertex no triangle uses
      const auto box = boxes.find(uint32_t(v));
      const bool keep =
          box == boxes.end()
              ? keepComponent(b, kMeasuredVertices + 1, glm::dvec3(0.0), glm::dvec3(0.0), cell)
              : keepComponent(b, kMeasuredVertices, box->second.lo, box->second.hi, cell);
      keepRoot[v] = keep ? 1 : 0;
      localDropped += keep ? 0 : 1;
    }
    droppedComponents += localDropped;
  });
  dropped.components = droppedComponents.load();
  if (dropped.components == 0) return dropped;
  // Where nothing would be left, the whole result is thinner than a cell: keep it, so that the
  // export says what it is (the evaluation warns of parts smaller than a cell) rather than fail.
  bool anyKept = false;
  for (size_t v = 0; v < n && !anyKept; ++v) anyKept = rootOf[v] == v && keepRoot[v];
  if (!anyKept) return DroppedSpecks();
  // Compact: triangles (with their leaves and bits), then vertices, in order.
  const size_t kept = compactInOrder(
      triangles.size(), [&](size_t t) { return keepRoot[rootOf[triangles[t][0]]] != 0; },
      [&](size_t from, size_t to, size_t count) {
        std::memmove(&triangles[to], &triangles[from], count * sizeof(triangles[0]));
        std::memmove(&mesh->triangleLeaf[to], &mesh->triangleLeaf[from],
                     count * sizeof(mesh->triangleLeaf[0]));
        std::memmove(&(*resolved)[to], &(*resolved)[from], count * sizeof((*resolved)[0]));
      });
  dropped.triangles = triangles.size() - kept;
  triangles.resize(kept);
  mesh->triangleLeaf.resize(kept);
  resolved->resize(kept);
  // Where each kept vertex goes: its rank among the kept (counts per fixed block, then ranks).
  constexpr size_t kBlock = 65536;
  std::vector<uint32_t> remap(n);
  std::vector<uint32_t> before((n + kBlock - 1) / kBlock + 1, 0);
  parallelFor(0, int64_t(before.size() - 1), 1, [&](int64_t b, int64_t e) {
    for (int64_t k = b; k < e; ++k) {
      uint32_t c = 0;
      for (size_t v = size_t(k) * kBlock; v < std::min(n, size_t(k + 1) * kBlock); ++v)
        c += keepRoot[rootOf[v]] ? 1 : 0;
      before[size_t(k) + 1] = c;
    }
  });
  for (size_t k = 1; k < before.size(); ++k) before[k] += before[k - 1];
  parallelFor(0, int64_t(before.size() - 1), 1, [&](int64_t b, int64_t e) {
    for (int64_t k = b; k < e; ++k) {
      uint32_t next = before[size_t(k)];
      for (size_t v = size_t(k) * kBlock; v < std::min(n, size_t(k + 1) * kBlock); ++v)
        remap[v] = keepRoot[rootOf[v]] ? next++ : UINT32_MAX;
    }
  });
  const size_t keptVertices = compactInOrder(
      n, [&](size_t v) { return remap[v] != UINT32_MAX; },
      [&](size_t from, size_t to, size_t count) {
        std::memmove(&positions[to], &positions[from], count * sizeof(positions[0]));
      });
  positions.resize(keptVertices);
  parallelFor(0, int64_t(kept), 65536, [&](int64_t b, int64_t e) {
    for (int64_t t = b; t < e; ++t)
      for (uint32_t& v : triangles[size_t(t)]) v = remap[v];
  });
  return dropped;
}

}  // namespace strata
