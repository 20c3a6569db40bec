// See unfold_shells.h.
#include "engine/export/unfold_shells.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <vector>

#include "engine/util/parallel_for.h"
#include "engine/util/union_find.h"

namespace strata {
namespace {

constexpr uint64_t kFaceVertexBit = uint64_t(1) << 63;  // faceSegmentKey (contour_cells.h)

// Six times the signed volume of one triangle (corners relative to a reference point).
double sixVolumeTerm(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  return glm::dot(a, glm::cross(b, c));
}

// Six times the signed volume of the shell's triangles with vertex positions `at(i)`, relative
// to `ref` (a point of the shell, so that the sum does not cancel far from the origin).
template <typename At>
double sixVolume(const TriangleMesh& mesh, const std::vector<uint32_t>& shellTriangles,
                 const glm::dvec3& ref, At at) {
  double sum = 0.0;
  for (uint32_t t : shellTriangles) {
    const auto& tri = mesh.triangles[t];
    const glm::dvec3 a = at(tri[0]) - ref, b = at(tri[1]) - ref, c = at(tri[2]) - ref;
    sum += sixVolumeTerm(a, b, c);
  }
  return sum;
}

int sign(double x) {
  return (x > 0.0) - (x < 0.0);
}

}  // namespace

int unfoldInvertedShells(const Grid& grid, const std::vector<uint64_t>& keys,
                         const std::vector<uint32_t>& rootOf, TriangleMesh* mesh) {
  const size_t n = mesh->positions.size();
  if (n == 0 || keys.size() != n || rootOf.size() != n) return 0;

  // Where each vertex goes at the grid's own placement: its cell's centre, or halfway there
  // when its cell has several components (their keys are adjacent: vertices are in key order).
  std::vector<glm::dvec3> anchor(n);
  parallelFor(0, int64_t(n), 65536, [&](int64_t b, int64_t e) {
    for (size_t i = size_t(b); i < size_t(e); ++i) {
      const uint64_t key = keys[i];
      if (key & kFaceVertexBit) {  // on a cell face, between two crossings: stays
        anchor[i] = mesh->positions[i];
        continue;
      }
      const uint64_t cell = key / 4;
      const uint64_t gx = uint64_t(grid.cells.x), gy = uint64_t(grid.cells.y);
      const glm::dvec3 index(double(cell % gx), double(cell / gx % gy), double(cell / gx / gy));
      const glm::dvec3 centre = grid.origin + grid.h * (index + 0.5);
      const bool shared =
          (i > 0 && keys[i - 1] / 4 == cell) || (i + 1 < n && keys[i + 1] / 4 == cell);
      anchor[i] = shared ? 0.5 * (centre + mesh->positions[i]) : centre;
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
  struct Run {
    uint32_t shell;
    double anchored, placed;
  };
  constexpr int64_t kChunk = 65536;
  std::vector<std::vector<Run>> runs(size_t((triangleCount + kChunk - 1) / kChunk));
  parallelFor(0, int64_t(runs.size()), 1, [&](int64_t b, int64_t e) {
    for (int64_t c = b; c < e; ++c) {
      std::vector<Run>& out = runs[size_t(c)];
      for (int64_t t = c * kChunk; t < std::min(triangleCount, (c + 1) * kChunk); ++t) {
        const auto& tri = triangles[size_t(t)];
        const uint32_t shell = shellOf[tri[0]];
        if (out.empty() || out.back().shell != shell) out.push_back({shell, 0.0, 0.0});
        const glm::dvec3& ref = sums[shell].ref;
        out.back().anchored +=
            sixVolumeTerm(anchor[tri[0]] - ref, anchor[tri[1]] - ref, anchor[tri[2]] - ref);
        out.back().placed +=
            sixVolumeTerm(mesh->positions[tri[0]] - ref, mesh->positions[tri[1]] - ref,
                          mesh->positions[tri[2]] - ref);
      }
    }
  });
  for (const std::vector<Run>& chunk : runs)
    for (const Run& run : chunk) {
      sums[run.shell].anchored += run.anchored;
      sums[run.shell].placed += run.placed;
    }
  runs = {};
  std::vector<uint8_t> inverted(shells, 0);
  bool any = false;
  for (uint32_t s = 0; s < shells; ++s) {
    const int want = sign(sums[s].anchored);
    inverted[s] = want != 0 && sign(sums[s].placed) != want;
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
    const glm::dvec3 ref = sums[s].ref;
    const int want = sign(sums[s].anchored);
    // Pulled back from the anchors: keep `keep` of each vertex's offset from its anchor.
    double keep = 0.5;
    for (;; keep *= 0.5) {
      const auto pulled = [&](uint32_t v) {
        return anchor[v] + keep * (mesh->positions[v] - anchor[v]);
      };
      if (keep < 1.0 / 64 || sign(sixVolume(*mesh, tris, ref, pulled)) == want) break;
    }
    if (keep < 1.0 / 64) keep = 0.0;
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
