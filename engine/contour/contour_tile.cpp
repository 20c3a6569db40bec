#include "engine/contour/contour_tile.h"

#include <glm/common.hpp>

#include <algorithm>
#include <atomic>

#include "engine/contour/contour_cells.h"
#include "engine/contour/tile_sides.h"
#include "engine/util/parallel_for.h"

namespace strata {
namespace {

constexpr CellCaseTable kCellCases = buildCellCaseTable();

// The tile's arrays on the host, and the view the shared per-cell steps read.
struct HostTile {
  TileSides sides;  // node sides and boundary cells (tile_sides.h)
  std::vector<uint32_t> vertexStart;
  TileView view{};
};

void placeVertices(HostTile& tile, TileContour* out, Progress* progress) {
  const size_t count = tile.sides.boundary.size();
  tile.vertexStart.assign(count + 1, 0);
  uint32_t total = 0;
  for (size_t b = 0; b < count; ++b) {
    tile.vertexStart[b] = total;
    total += uint32_t(kCellCases.cases[tile.sides.boundaryMasks[b]].components);
  }
  tile.vertexStart[count] = total;
  out->vertices.resize(total);
  parallelFor(0, int64_t(count), 2048, [&](int64_t first, int64_t last) {
    if (progress) progress->check();
    for (int64_t b = first; b < last; ++b)
      placeCellVertices(tile.view, kCellCases, b,
                        out->vertices.data() + tile.vertexStart[size_t(b)]);
  });
  tile.view.vertexStart = tile.vertexStart.data();
  tile.view.vertices = out->vertices.data();
}

void emitPolygons(HostTile& tile, TileContour* out, Progress* progress) {
  const size_t count = tile.sides.boundary.size();
  constexpr int64_t kGrain = 4096;
  const size_t chunkCount = size_t((int64_t(count) + kGrain - 1) / kGrain);
  std::vector<std::vector<ContourTriangle>> chunks(chunkCount);
  std::vector<std::vector<ContourVertex>> faceVertices(chunkCount);
  std::atomic<uint64_t> synthesized{0};
  parallelFor(0, int64_t(count), kGrain, [&](int64_t first, int64_t last) {
    if (progress) progress->check();
    std::vector<ContourTriangle>& tris = chunks[size_t(first / kGrain)];
    std::vector<ContourVertex>& extra = faceVertices[size_t(first / kGrain)];
    int localSynthesized = 0;
    CellTriangle cellTris[kMaxCellTriangles];
    CellVertex cellFaces[kMaxCellFaceVertices];
    for (int64_t b = first; b < last; ++b) {
      int faces = 0;
      const int n =
          cellPolygons(tile.view, kCellCases, b, cellTris, cellFaces, &faces, &localSynthesized);
      tris.insert(tris.end(), cellTris, cellTris + n);
      extra.insert(extra.end(), cellFaces, cellFaces + faces);
    }
    synthesized += uint64_t(localSynthesized);
  });
  size_t total = 0;
  for (const auto& c : chunks) total += c.size();
  out->triangles.reserve(total);
  for (auto& c : chunks) out->triangles.insert(out->triangles.end(), c.begin(), c.end());
  for (auto& f : faceVertices) out->vertices.insert(out->vertices.end(), f.begin(), f.end());
  out->synthesizedCrossings = synthesized.load();
}

}  // namespace

TileWindow tileWindow(const glm::ivec3& begin, const glm::ivec3& end, const glm::ivec3& cells) {
  TileWindow w;
  w.first = glm::max(begin - 1, glm::ivec3(0));
  glm::ivec3 last = glm::min(end, cells);
  w.cells = last - w.first;
  return w;
}

TileView makeTileView(const glm::ivec3& first, const glm::ivec3& cells,
                      const glm::ivec3& globalCells, const glm::ivec3& begin,
                      const glm::ivec3& end) {
  TileView v{};
  for (int k = 0; k < 3; ++k) {
    v.first[k] = first[k];
    v.cells[k] = cells[k];
    v.globalCells[k] = globalCells[k];
    v.ownedLo[k] = begin[k] - first[k];
    v.ownedHi[k] = end[k] - first[k];
  }
  return v;
}

TileContour contourTile(const Ldi& ldi, const glm::ivec3& globalCells, const glm::ivec3& begin,
                        const glm::ivec3& end, Progress* progress) {
  HostTile tile;
  tile.view = makeTileView(ldi.grid.first, ldi.grid.cells, globalCells, begin, end);
  for (int a = 0; a < 3; ++a) {
    tile.view.offsets[a] = ldi.axes[a].offsets.data();
    tile.view.surfels[a] = ldi.axes[a].surfels.data();
  }
  TileContour out;
  decideTileSides(&tile.view, &tile.sides, progress);
  out.signDisagreements = tile.sides.disagreements;
  placeVertices(tile, &out, progress);
  emitPolygons(tile, &out, progress);
  return out;
}

}  // namespace strata
