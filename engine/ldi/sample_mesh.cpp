#include "engine/ldi/sample_mesh.h"

#include "engine/ldi/grid_mesh.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "engine/geometry/transform.h"
#include "engine/util/error.h"
#include "engine/util/parallel_for.h"

namespace strata {
namespace {

constexpr int64_t kRayGrain = 8192;

ProjectedTriangle project(const GridMesh& g, size_t t, int axis, const Grid& grid) {
  double p[3][3];
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 3; ++k) p[c][k] = g.positions[g.triangles[t][c]][k];
  const double n[3] = {g.normals[t].x, g.normals[t].y, g.normals[t].z};
  return projectTriangle(p, n, axis, grid.first[grid.uAxis(axis)], grid.first[grid.vAxis(axis)],
                         grid.raysU(axis), grid.raysV(axis));
}

// The rays any triangle of g may hit along `axis`: the bounding window of their ray ranges.
RayWindow candidateWindow(const GridMesh& g, const Grid& grid, int axis, int64_t triangleGrain,
                          Progress* progress) {
  const int64_t triangles = int64_t(g.triangles.size());
  const int64_t chunks = (triangles + triangleGrain - 1) / triangleGrain;
  struct Range {
    int uMin = std::numeric_limits<int>::max(), uMax = -1;
    int vMin = std::numeric_limits<int>::max(), vMax = -1;
  };
  std::vector<Range> ranges(size_t(std::max<int64_t>(chunks, 1)));
  parallelFor(0, triangles, triangleGrain, [&](int64_t b, int64_t e) {
    if (progress) progress->check();
    Range& r = ranges[size_t(b / triangleGrain)];
    for (int64_t t = b; t < e; ++t) {
      const ProjectedTriangle pt = project(g, size_t(t), axis, grid);
      if (pt.rayUMin > pt.rayUMax || pt.rayVMin > pt.rayVMax) continue;
      r.uMin = std::min(r.uMin, pt.rayUMin);
      r.uMax = std::max(r.uMax, pt.rayUMax);
      r.vMin = std::min(r.vMin, pt.rayVMin);
      r.vMax = std::max(r.vMax, pt.rayVMax);
    }
  });
  Range all;
  for (const Range& r : ranges) {
    all.uMin = std::min(all.uMin, r.uMin);
    all.uMax = std::max(all.uMax, r.uMax);
    all.vMin = std::min(all.vMin, r.vMin);
    all.vMax = std::max(all.vMax, r.vMax);
  }
  if (all.uMax < 0 || all.vMax < 0) return RayWindow{};
  return RayWindow{all.uMin, all.vMin, all.uMax - all.uMin + 1, all.vMax - all.vMin + 1};
}

void sampleAxis(const GridMesh& g, const Grid& grid, int axis, uint32_t leafId, Progress* progress,
                AxisLdi* out) {
  const int64_t triangles = int64_t(g.triangles.size());
  // Enough chunks to balance big and small triangles over the workers.
  const int64_t triangleGrain = std::max<int64_t>(64, triangles / (int64_t(workerCount()) * 16));
  // Only the rays the triangles can reach get counters and offsets: a small part of a big grid
  // costs its size, not the grid's.
  const RayWindow window = candidateWindow(g, grid, axis, triangleGrain, progress);
  const int64_t rays = window.rayCount();
  const int64_t raysU = window.uCount;
  std::unique_ptr<std::atomic<uint32_t>[]> counts(new std::atomic<uint32_t>[size_t(rays)]);
  for (int64_t r = 0; r < rays; ++r) counts[r].store(0, std::memory_order_relaxed);

  // Pass 1: count the hits of every ray.
  parallelFor(0, triangles, triangleGrain, [&](int64_t b, int64_t e) {
    if (progress) progress->check();
    for (int64_t t = b; t < e; ++t) {
      ProjectedTriangle pt = project(g, size_t(t), axis, grid);
      for (int j = pt.rayVMin; j <= pt.rayVMax; ++j) {
        int first, last;  // the row's hits (hitTriangle), a run
        triangleRowSpan(pt, j, &first, &last);
        const int64_t row = int64_t(j - window.v0) * raysU - window.u0;
        for (int i = first; i <= last; ++i) counts[row + i].fetch_add(1, std::memory_order_relaxed);
      }
    }
  });
  // Exclusive scan into raw offsets.
  std::vector<uint64_t> rawOffsets(size_t(rays) + 1);
  uint64_t total = 0;
  for (int64_t r = 0; r < rays; ++r) {
    rawOffsets[size_t(r)] = total;
    total += counts[r].load(std::memory_order_relaxed);
    counts[r].store(0, std::memory_order_relaxed);  // reused as write cursors
  }
  rawOffsets[size_t(rays)] = total;
  HostArray<Surfel> raw(total);  // every slot written by pass 2

  // Pass 2: write each hit at its ray's next slot.
  parallelFor(0, triangles, triangleGrain, [&](int64_t b, int64_t e) {
    if (progress) progress->check();
    for (int64_t t = b; t < e; ++t) {
      ProjectedTriangle pt = project(g, size_t(t), axis, grid);
      for (int j = pt.rayVMin; j <= pt.rayVMax; ++j) {
        int first, last;  // the same run as pass 1's
        triangleRowSpan(pt, j, &first, &last);
        const int64_t row = int64_t(j - window.v0) * raysU - window.u0;
        for (int i = first; i <= last; ++i) {
          const int64_t r = row + i;
          const uint32_t slot = counts[r].fetch_add(1, std::memory_order_relaxed);
          raw[rawOffsets[size_t(r)] + slot] =
              Surfel{float(hitDepth(pt, i, j)), pt.normal, makeSurfelTag(leafId, pt.enters)};
        }
      }
    }
  });
  counts.reset();

  // Pass 3: sort each ray's hits and normalise them into a clean list.
  const float lo = clipLo(grid, axis), hi = clipHi(grid, axis);
  uint32_t minus =
      encodeNormal(axis == 0 ? -1.f : 0.f, axis == 1 ? -1.f : 0.f, axis == 2 ? -1.f : 0.f);
  uint32_t plus = encodeNormal(axis == 0 ? 1.f : 0.f, axis == 1 ? 1.f : 0.f, axis == 2 ? 1.f : 0.f);
  const int64_t chunkCount = (rays + kRayGrain - 1) / kRayGrain;
  std::vector<RayChunkOutput> chunks(static_cast<size_t>(chunkCount));
  parallelFor(0, rays, kRayGrain, [&](int64_t b, int64_t e) {
    if (progress) progress->check();
    RayChunkOutput& chunk = chunks[size_t(b / kRayGrain)];
    chunk.counts.resize(size_t(e - b));
    for (int64_t r = b; r < e; ++r) {
      Surfel* first = raw.data() + rawOffsets[size_t(r)];
      int n = int(rawOffsets[size_t(r) + 1] - rawOffsets[size_t(r)]);
      std::sort(first, first + n, surfelLess);
      size_t at = chunk.surfels.size();
      chunk.surfels.resize(at + size_t(n) + 2);
      int written =
          normalizeLeafRay(first, n, lo, hi, leafId, minus, plus, chunk.surfels.data() + at);
      chunk.surfels.resize(at + size_t(written));
      chunk.counts[size_t(r - b)] = uint32_t(written);
    }
  });
  raw.clear();
  raw.shrink_to_fit();
  assembleAxis(chunks, rays, out, "sampling");
  settleAxisWindow(grid, axis, window, out);
}

}  // namespace

void assembleAxis(std::vector<RayChunkOutput>& chunks, int64_t rayCount, AxisLdi* axis,
                  const char* what) {
  axis->offsets.assign(size_t(rayCount) + 1, 0u);
  std::vector<uint64_t> chunkStart(chunks.size() + 1, 0);
  for (size_t c = 0; c < chunks.size(); ++c)
    chunkStart[c + 1] = chunkStart[c] + chunks[c].surfels.size();
  checkSurfelCount(chunkStart.back(), what);
  axis->surfels.resize(size_t(chunkStart.back()));
  int64_t ray = 0;
  for (size_t c = 0; c < chunks.size(); ++c) {
    uint32_t offset = uint32_t(chunkStart[c]);
    for (uint32_t count : chunks[c].counts) {
      axis->offsets[size_t(ray++)] = offset;
      offset += count;
    }
  }
  axis->offsets[size_t(rayCount)] = uint32_t(chunkStart.back());
  parallelFor(0, int64_t(chunks.size()), 1, [&](int64_t b, int64_t e) {
    for (int64_t c = b; c < e; ++c) {
      std::copy(chunks[size_t(c)].surfels.begin(), chunks[size_t(c)].surfels.end(),
                axis->surfels.begin() + int64_t(chunkStart[size_t(c)]));
      chunks[size_t(c)] = RayChunkOutput();
    }
  });
}

std::shared_ptr<Ldi> sampleMesh(const TriangleMesh& mesh, const glm::dmat4& objectToWorld,
                                const Grid& grid, uint32_t leafId, Progress* progress) {
  GridMesh g = toGridUnits(mesh, objectToWorld, grid);
  auto ldi = std::make_shared<Ldi>();
  ldi->grid = grid;
  for (int axis = 0; axis < 3; ++axis) {
    sampleAxis(g, grid, axis, leafId, progress, &ldi->axes[axis]);
    if (progress) progress->check();
  }
  return ldi;
}

}  // namespace strata
