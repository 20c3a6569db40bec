#include "engine/contour/contour_tile.h"

#include <glm/common.hpp>

#include <algorithm>
#include <atomic>
#include <memory>

#include "engine/contour/contour_cells.h"
#include "engine/util/parallel_for.h"

namespace strata {
namespace {

constexpr CellCaseTable kCellCases = buildCellCaseTable();

// Bytes left uninitialised: every one is written by a parallel loop before it is read, so the
// pages are first touched (and zeroed by the kernel) on all workers, not by one thread filling
// gigabytes with zeros that the loop then overwrites (a tile of 1024 cells holds 3 GB).
class ByteArray {
 public:
  void reset(size_t size) {
    data_.reset(new uint8_t[size]);  // default-initialised: no fill
    size_ = size;
  }
  uint8_t* data() { return data_.get(); }
  size_t size() const { return size_; }
  uint8_t& operator[](size_t i) { return data_[i]; }

 private:
  std::unique_ptr<uint8_t[]> data_;
  size_t size_ = 0;
};

// The tile's arrays on the host, and the view the shared per-cell steps read.
struct HostTile {
  ByteArray votes;                 // per window node: rays saying inside
  ByteArray inside;                // per window node
  ByteArray masks;                 // per window cell
  std::vector<uint32_t> boundary;  // boundary cells, increasing index
  std::vector<uint32_t> vertexStart;
  TileView view{};
};

// The node votes (decideNodeSide): every ray walks its surfels once (startRayVote, rayVote)
// while the loops run over nodes in memory order (x fastest), keeping one cursor per ray of the
// current row or slab, so all writes are sequential. votes[node] = the x and y rays' votes.
void voteAlongXAndY(const TileView& t, ByteArray& votes, Progress* progress) {
  const int nx = t.cells[0] + 1, ny = t.cells[1] + 1, nz = t.cells[2] + 1;
  const int64_t plane = int64_t(nx) * ny;
  parallelFor(0, nz, 1, [&](int64_t b, int64_t e) {
    if (progress) progress->check();
    std::vector<RayVoteCursor> yCursors(static_cast<size_t>(nx));
    for (int k = int(b); k < int(e); ++k) {
      for (int i = 0; i < nx; ++i) {
        const int node[3] = {i, 0, k};
        yCursors[size_t(i)] = startRayVote(t, 1, node);
      }
      for (int j = 0; j < ny; ++j) {
        uint8_t* row = votes.data() + plane * k + int64_t(nx) * j;
        const int node[3] = {0, j, k};
        RayVoteCursor xc = startRayVote(t, 0, node);
        for (int i = 0; i < nx; ++i)
          row[i] = uint8_t(rayVote(t, 0, xc, i) + rayVote(t, 1, yCursors[size_t(i)], j));
      }
    }
  });
}

// votes[node] += the z rays' votes (as above).
void addVotesAlongZ(const TileView& t, ByteArray& votes, Progress* progress) {
  const int nx = t.cells[0] + 1, ny = t.cells[1] + 1, nz = t.cells[2] + 1;
  const int64_t plane = int64_t(nx) * ny;
  parallelFor(0, ny, 1, [&](int64_t b, int64_t e) {
    if (progress) progress->check();
    std::vector<RayVoteCursor> zCursors(static_cast<size_t>(nx));
    for (int j = int(b); j < int(e); ++j) {
      for (int i = 0; i < nx; ++i) {
        const int node[3] = {i, j, 0};
        zCursors[size_t(i)] = startRayVote(t, 2, node);
      }
      for (int k = 0; k < nz; ++k) {
        uint8_t* row = votes.data() + plane * k + int64_t(nx) * j;
        for (int i = 0; i < nx; ++i)
          row[i] = uint8_t(row[i] + rayVote(t, 2, zCursors[size_t(i)], k));
      }
    }
  });
}

// Majority of the three rays through each window node, and outside on the grid's outer faces
// (decideNodeSide), into tile.inside. Returns the number of nodes whose rays disagreed.
uint64_t decideNodeSigns(HostTile& tile, Progress* progress) {
  const TileView& t = tile.view;
  const int nx = t.cells[0] + 1, ny = t.cells[1] + 1, nz = t.cells[2] + 1;
  const int64_t plane = int64_t(nx) * ny;
  ByteArray& votes = tile.votes;
  votes.reset(size_t(plane * nz));  // every node written by voteAlongXAndY
  voteAlongXAndY(t, votes, progress);
  addVotesAlongZ(t, votes, progress);
  std::atomic<uint64_t> disagreements{0};
  tile.inside.reset(votes.size());  // every node written below
  parallelFor(0, nz, 1, [&](int64_t b, int64_t e) {
    uint64_t local = 0;
    for (int k = int(b); k < int(e); ++k) {
      const int gz = t.first[2] + k;
      const bool zFace = gz == 0 || gz == t.globalCells[2];
      for (int j = 0; j < ny; ++j) {
        const int gy = t.first[1] + j;
        const bool yFace = zFace || gy == 0 || gy == t.globalCells[1];
        const size_t at = size_t(plane * k + int64_t(nx) * j);
        for (int i = 0; i < nx; ++i) {
          const int gx = t.first[0] + i;
          const uint8_t vote = votes[at + size_t(i)];
          local += (vote == 1 || vote == 2) ? 1 : 0;
          tile.inside[at + size_t(i)] =
              decideNodeSide(vote, yFace || gx == 0 || gx == t.globalCells[0]);
        }
      }
    }
    disagreements += local;
  });
  tile.view.inside = tile.inside.data();
  tile.view.votes = tile.votes.data();
  return disagreements.load();
}

// The corner mask of every window cell, and the boundary cells in increasing index.
void computeCellMasks(HostTile& tile, Progress* progress) {
  const TileView& t = tile.view;
  tile.masks.reset(size_t(int64_t(t.cells[0]) * t.cells[1] * t.cells[2]));  // every cell written
  std::vector<std::vector<uint32_t>> slabs(size_t(t.cells[2]));
  parallelFor(0, t.cells[2], 1, [&](int64_t b, int64_t e) {
    if (progress) progress->check();
    for (int k = int(b); k < int(e); ++k)
      for (int j = 0; j < t.cells[1]; ++j) {
        const int64_t row = tileCell(t, 0, j, k);
        for (int i = 0; i < t.cells[0]; ++i) {
          const uint8_t mask = cellMaskFromNodes(t, i, j, k);
          tile.masks[size_t(row + i)] = mask;
          if (mask != 0 && mask != 255) slabs[size_t(k)].push_back(uint32_t(row + i));
        }
      }
  });
  tile.boundary.clear();
  for (const auto& slab : slabs)
    tile.boundary.insert(tile.boundary.end(), slab.begin(), slab.end());
  tile.view.masks = tile.masks.data();
  tile.view.boundary = tile.boundary.data();
  tile.view.boundaryCount = int64_t(tile.boundary.size());
}

void placeVertices(HostTile& tile, TileContour* out, Progress* progress) {
  const size_t count = tile.boundary.size();
  tile.vertexStart.assign(count + 1, 0);
  uint32_t total = 0;
  for (size_t b = 0; b < count; ++b) {
    tile.vertexStart[b] = total;
    total += uint32_t(kCellCases.cases[tile.masks[tile.boundary[b]]].components);
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
  const size_t count = tile.boundary.size();
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
  out.signDisagreements = decideNodeSigns(tile, progress);
  computeCellMasks(tile, progress);
  placeVertices(tile, &out, progress);
  emitPolygons(tile, &out, progress);
  return out;
}

}  // namespace strata
