// See unfold_shells.h.
#include "engine/export/unfold_shells.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <vector>

#include "engine/util/parallel_for.h"
#include "engine/util/union_find.h"

namespace strata {
namespace {

constexpr uint64_t kFaceVertexBit = uint64_t(1) << 63;  // faceSegmentKey (contour_cells.h)

}  // namespace

double sixVolumeTerm(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  return glm::dot(a, glm::cross(b, c));
}

int volumeSign(double x) {
  return (x > 0.0) - (x < 0.0);
}

glm::dvec3 shellAnchor(const Grid& grid, uint64_t key, bool sharedCell,
                       const glm::dvec3& position) {
  if (key & kFaceVertexBit) return position;  // on a cell face, between two crossings: stays
  const uint64_t cell = key / 4;
  const uint64_t gx = uint64_t(grid.cells.x), gy = uint64_t(grid.cells.y);
  const glm::dvec3 index(double(cell % gx), double(cell / gx % gy), double(cell / gx / gy));
  const glm::dvec3 centre = grid.origin + grid.h * (index + 0.5);
  return sharedCell ? 0.5 * (centre + position) : centre;
}

double pullBackKeep(const std::vector<std::array<uint32_t, 3>>& triangles,
                    const std::vector<glm::dvec3>& anchors,
                    const std::vector<glm::dvec3>& positions, const glm::dvec3& ref, int want) {
  double keep = 0.5;
  for (;; keep *= 0.5) {
    if (keep < 1.0 / 64) break;
    double sum = 0.0;
    for (const auto& tri : triangles) {
      glm::dvec3 p[3];
      for (int k = 0; k < 3; ++k)
        p[k] = anchors[tri[size_t(k)]] +
               keep * (positions[tri[size_t(k)]] - anchors[tri[size_t(k)]]) - ref;
      sum += sixVolumeTerm(p[0], p[1], p[2]);
    }
    if (volumeSign(sum) == want) break;
  }
  return keep < 1.0 / 64 ? 0.0 : keep;
}

int unfoldInvertedShells(const Grid& grid, const std::vector<uint64_t>& keys,
                         const std::vector<uint32_t>& rootOf, TriangleMesh* mesh) {
  const size_t n = mesh->positions.size();
  if (n == 0 || keys.size() != n || rootOf.size() != n) return 0;

  // Where each vertex goes at the grid's own placement: its cell's centre, or halfway there
  // when its cell has several components (their keys are adjacent: vertices are in key order).
  std::vector<glm::dvec3> anchor(n);
  parallelFor(0, int64_t(n), 65536, [&](int64_t b, int64_t e) {
    for (size_t i = size_t(b); i < size_t(e); ++i) {
      anchor[i] = shellAnchor(grid, keys[i], sharesCell(keys, i), mesh->positions[i]);
    }
  });

  // Shells: triangles joined through shared vertices, numbered by their first vertex (a root is
  // its component's smallest vertex: shells are the roots' ranks).
  uint32_t shells = 0;
  const std::vector<uint32_t> shellOf = numberSetsByRoot(rootOf, &shells);

  // Each shell's six volumes, anchored and placed, relative to its first triangle's first
  // anchor: summed in parallel over fixed chunks of triangles (runs of one shell in a chunk
  // summed in order, the runs then added chunk by chunk in order: the same sums on any thread
  // count). Most triangles are in one shell: one atomic per run, not per triangle.
  const auto& triangles = mesh->triangles;
  const int64_t triangleCount = int64_t(triangles.size());
  std::vector<std::atomic<uint32_t>> firstTriangle(shells);
  for (auto& f : firstTriangle) f.store(UINT32_MAX, std::memory_order_relaxed);
  parallelFor(0, triangleCount, 65536, [&](int64_t b, int64_t e) {
    uint32_t previous = UINT32_MAX;
    for (int64_t t = b; t < e; ++t) {
      const uint32_t shell = shellOf[triangles[size_t(t)][0]];
      if (shell == previous) continue;
      previous = shell;
      uint32_t seen = firstTriangle[shell].load(std::memory_order_relaxed);
      while (uint32_t(t) < seen && !firstTriangle[shell].compare_exchange_weak(seen, uint32_t(t))) {
      }
    }
  });
  struct ShellSums {
    glm::dvec3 ref{0.0};
    double anchored = 0.0, placed = 0.0;
  };
  std::vector<ShellSums> sums(shells);
  for (uint32_t s = 0; s < shells; ++s)
    if (firstTriangle[s].load() != UINT32_MAX) sums[s].ref = anchor[triangles[firstTriangle[s]][0]];
  firstTriangle = std::vector<std::atomic<uint32_t>>();
  ShellRunSums runs;
  const auto flush = [&](const ShellRun& run) {
    sums[run.shell].anchored += run.anchored;
    sums[run.shell].placed += run.placed;
  };
  runs.add(
      uint64_t(triangleCount),
      [&](uint64_t t, uint32_t* shell, double* anchored, double* placed) {
        const auto& tri = triangles[size_t(t)];
        *shell = shellOf[tri[0]];
        const glm::dvec3& ref = sums[*shell].ref;
        *anchored = sixVolumeTerm(anchor[tri[0]] - ref, anchor[tri[1]] - ref, anchor[tri[2]] - ref);
        *placed = sixVolumeTerm(mesh->positions[tri[0]] - ref, mesh->positions[tri[1]] - ref,
                                mesh->positions[tri[2]] - ref);
      },
      flush);
  runs.finish(flush);
  std::vector<uint8_t> inverted(shells, 0);
  bool any = false;
  for (uint32_t s = 0; s < shells; ++s) {
    const int want = volumeSign(sums[s].anchored);
    inverted[s] = want != 0 && volumeSign(sums[s].placed) != want;
    any = any || inverted[s];
  }
  if (!any) return 0;

  // The inverted shells' triangles (few), each shell pulled back from its anchors.
  std::vector<std::vector<uint32_t>> shellTriangles(shells);
  for (size_t t = 0; t < triangles.size(); ++t)
    if (inverted[shellOf[triangles[t][0]]])
      shellTriangles[shellOf[triangles[t][0]]].push_back(uint32_t(t));
  int moved = 0;
  std::vector<bool> done(n, false);  // a vertex belongs to one shell: moved once
  for (uint32_t s = 0; s < shells; ++s) {
    if (!inverted[s]) continue;
    const std::vector<uint32_t>& tris = shellTriangles[s];
    std::vector<std::array<uint32_t, 3>> corners(tris.size());
    for (size_t k = 0; k < tris.size(); ++k) corners[k] = mesh->triangles[tris[k]];
    const double keep =
        pullBackKeep(corners, anchor, mesh->positions, sums[s].ref, volumeSign(sums[s].anchored));
    for (uint32_t t : tris)
      for (uint32_t v : mesh->triangles[t]) {
        if (done[v]) continue;
        done[v] = true;
        mesh->positions[v] = anchor[v] + keep * (mesh->positions[v] - anchor[v]);
      }
    ++moved;
  }
  return moved;
}

}  // namespace strata
