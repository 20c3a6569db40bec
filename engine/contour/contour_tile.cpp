#include "engine/contour/contour_tile.h"

#include <glm/common.hpp>

#include <algorithm>
#include <atomic>

#include "engine/contour/contour_cells.h"
#include "engine/contour/tile_sides.h"
#include "engine/util/error.h"
#include "engine/util/parallel_for.h"

namespace strata {
namespace {

constexpr CellCaseTable kCellCases = buildCellCaseTable();

// The tile's arrays on the host, and the view the shared per-cell steps read.
struct HostTile {
  explicit HostTile(TileSides& s) : sides(s) {}
  TileSides& sides;  // node sides and boundary cells (tile_sides.h)
  std::vector<uint32_t> vertexStart;
  std::vector<uint32_t> boundaryRowStart;  // TileView::boundaryRowStart
  HostArray<uint32_t> cornerCrossings;     // TileView::cornerCrossings, written by placeVertices
  TileView view{};
};

// Where each row of cells along x starts in the boundary cells (they come in increasing index),
// so that the polygon step finds a neighbouring cell's vertices within its row, not by a search
// over all of them (which took half of the polygon step at 1024 cells).
void indexBoundaryRows(HostTile& tile) {
  const std::vector<uint32_t>& boundary = tile.sides.boundary;
  const int64_t rows = int64_t(tile.view.cells[1]) * tile.view.cells[2];
  const uint32_t cellsX = uint32_t(tile.view.cells[0]);
  tile.boundaryRowStart.resize(size_t(rows) + 1);
  int64_t row = 0;
  for (size_t b = 0; b < boundary.size(); ++b) {
    const int64_t of = int64_t(boundary[b] / cellsX);
    while (row <= of) tile.boundaryRowStart[size_t(row++)] = uint32_t(b);
  }
  while (row <= rows) tile.boundaryRowStart[size_t(row++)] = uint32_t(boundary.size());
  tile.view.boundaryRowStart = tile.boundaryRowStart.data();
}

// Boundary cells placed together: placeCellVerticesTogether.
constexpr int kCellsTogether = 4;

// placeCellVertices of boundary cells b .. b + cells - 1 (cells <= kCellsTogether) into
// `vertices` at their vertexStart, with the decompositions of all their QEFs made kEigenBatch
// at a time (symmetricEigen3Batch: the same bits, more throughput than one at a time; the
// decompositions are most of the vertices' cost).
void placeCellVerticesTogether(const TileView& t, int64_t b, int cells, CellVertex* vertices) {
  CellPlanes planes[kCellsTogether];
  double m[kCellsTogether][kMaxCellComponents][3][3], v[kCellsTogether][kMaxCellComponents][3][3];
  double(*ms[kCellsTogether * kMaxCellComponents])[3];
  double(*vs[kCellsTogether * kMaxCellComponents])[3];
  int count = 0;
  for (int i = 0; i < cells; ++i) {
    gatherCellPlanes(t, kCellCases, b + i, &planes[i]);
    for (int comp = 0; comp < planes[i].components; ++comp) {
      qefMatrix(planes[i].qef[comp], m[i][comp]);
      ms[count] = m[i][comp];
      vs[count] = v[i][comp];
      ++count;
    }
  }
  for (int k = 0; k < count; k += kEigenBatch)
    symmetricEigen3Batch(ms + k, vs + k, std::min(kEigenBatch, count - k));
  for (int i = 0; i < cells; ++i) {
    finishCellVertices(t, planes[i], m[i], v[i], vertices + t.vertexStart[b + i]);
    keepCornerCrossings(t, b + i, planes[i]);
  }
}

// Boundary cells per chunk of the vertex and polygon steps.
constexpr int64_t kGrain = 4096;

// Where each chunk of kGrain boundary cells writes its triangles and face-segment vertices:
// counted from the corner signs first (cellPolygonCounts), so that the polygon step writes
// straight into the tile's arrays, sized once (no per-chunk arrays grown and copied together).
struct ChunkStarts {
  std::vector<uint64_t> triangles;  // per chunk, and the total last
  std::vector<uint64_t> faces;      // face vertices after the cell vertices, likewise
};

ChunkStarts countPolygons(const HostTile& tile, Progress* progress) {
  const int64_t count = int64_t(tile.sides.boundary.size());
  const size_t chunkCount = size_t((count + kGrain - 1) / kGrain);
  ChunkStarts starts;
  starts.triangles.assign(chunkCount + 1, 0);
  starts.faces.assign(chunkCount + 1, 0);
  parallelFor(0, count, kGrain, [&](int64_t first, int64_t last) {
    if (progress) progress->check();
    uint64_t triangles = 0, faces = 0;
    for (int64_t b = first; b < last; ++b) {
      int f = 0;
      triangles += uint64_t(cellPolygonCounts(tile.view, kCellCases, b, &f));
      faces += uint64_t(f);
    }
    starts.triangles[size_t(first / kGrain)] = triangles;
    starts.faces[size_t(first / kGrain)] = faces;
  });
  uint64_t triangles = 0, faces = 0;
  for (size_t c = 0; c <= chunkCount; ++c) {
    const uint64_t t = starts.triangles[c], f = starts.faces[c];
    starts.triangles[c] = triangles;
    starts.faces[c] = faces;
    triangles += t;
    faces += f;
  }
  return starts;
}

// The cell vertices, then room for `faces` face-segment vertices after them.
void placeVertices(HostTile& tile, uint64_t faces, TileContour* out, Progress* progress) {
  const size_t count = tile.sides.boundary.size();
  tile.vertexStart.assign(count + 1, 0);
  uint32_t total = 0;
  for (size_t b = 0; b < count; ++b) {
    tile.vertexStart[b] = total;
    total += uint32_t(kCellCases.cases[tile.sides.boundaryMasks[b]].components);
  }
  tile.vertexStart[count] = total;
  out->vertices.resize(total + faces);
  tile.view.vertexStart = tile.vertexStart.data();
  tile.cornerCrossings.resize(count * 3);  // every entry written with its cell's vertices
  tile.view.cornerCrossings = tile.cornerCrossings.data();
  parallelFor(0, int64_t(count), kGrain, [&](int64_t first, int64_t last) {
    if (progress) progress->check();
    for (int64_t b = first; b < last; b += kCellsTogether)
      placeCellVerticesTogether(tile.view, b, int(std::min<int64_t>(kCellsTogether, last - b)),
                                out->vertices.data());
  });
  tile.view.vertices = out->vertices.data();
}

void emitPolygons(HostTile& tile, const ChunkStarts& starts, TileContour* out, Progress* progress) {
  const int64_t count = int64_t(tile.sides.boundary.size());
  const size_t cellVertices = tile.vertexStart[size_t(count)];
  out->triangles.resize(starts.triangles.back());
  std::atomic<uint64_t> synthesized{0};
  parallelFor(0, count, kGrain, [&](int64_t first, int64_t last) {
    if (progress) progress->check();
    const size_t chunk = size_t(first / kGrain);
    ContourTriangle* tris = out->triangles.data() + starts.triangles[chunk];
    ContourVertex* faces = out->vertices.data() + cellVertices + starts.faces[chunk];
    const ContourTriangle* trisEnd = out->triangles.data() + starts.triangles[chunk + 1];
    const ContourVertex* facesEnd = out->vertices.data() + cellVertices + starts.faces[chunk + 1];
    int localSynthesized = 0;
    for (int64_t b = first; b < last; ++b) {
      int faceCount = 0;
      tris += cellPolygons(tile.view, kCellCases, b, tris, faces, &faceCount, &localSynthesized);
      faces += faceCount;
    }
    // The count and the polygons disagreeing would leave stale or overwritten entries.
    if (tris != trisEnd || faces != facesEnd)
      throw Error("contour: a chunk's polygons differ from their count (internal error)");
    synthesized += uint64_t(localSynthesized);
  });
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
                        const glm::ivec3& end, Progress* progress, TileSides* reuse) {
  TileSides own;
  HostTile tile(reuse ? *reuse : own);
  tile.view = makeTileView(ldi.grid.first, ldi.grid.cells, globalCells, begin, end);
  for (int a = 0; a < 3; ++a) {
    tile.view.offsets[a] = ldi.axes[a].offsets.data();
    tile.view.surfels[a] = ldi.axes[a].surfels.data();
  }
  TileContour out;
  decideTileSides(&tile.view, &tile.sides, progress);
  out.signDisagreements = tile.sides.disagreements;
  indexBoundaryRows(tile);
  const ChunkStarts starts = countPolygons(tile, progress);
  placeVertices(tile, starts.faces.back(), &out, progress);
  emitPolygons(tile, starts, &out, progress);
  return out;
}

}  // namespace strata
