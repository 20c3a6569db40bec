#include <thrust/iterator/counting_iterator.h>
#include <cub/device/device_scan.cuh>
#include <cub/device/device_select.cuh>

#include <mutex>
#include <vector>

#include "engine/contour/contour_cells.h"
#include "gpu/contour/contour_tile.cuh"
#include "gpu/ldi/csr_build.cuh"

namespace strata {
namespace {

__constant__ CellCaseTable c_cellCases;

// The cell case table in constant memory, uploaded once per device (constant memory is each
// device's own: a table uploaded to device 0 alone left device 1's zero, and the export's second
// GPU faulted), on the first caller's stream there, waited for before any caller goes on. The
// caller has made the stream's device current.
void uploadCellCases(const DeviceStream& stream) {
  int device = 0;
  STRATA_CUDA_CHECK(cudaGetDevice(&device));
  static std::mutex mutex;
  static std::vector<bool> uploaded;  // by device
  std::lock_guard<std::mutex> lock(mutex);
  if (size_t(device) < uploaded.size() && uploaded[size_t(device)]) return;
  const CellCaseTable table = buildCellCaseTable();
  STRATA_CUDA_CHECK(cudaMemcpyToSymbolAsync(c_cellCases, &table, sizeof(table), 0,
                                            cudaMemcpyHostToDevice, stream.get()));
  STRATA_CUDA_CHECK(cudaStreamSynchronize(stream.get()));
  if (uploaded.size() <= size_t(device)) uploaded.resize(size_t(device) + 1, false);
  uploaded[size_t(device)] = true;
}

// Votes of one axis: one thread per ray walks its surfels and its nodes together.
__global__ void voteAxis(TileView t, int axis, uint8_t* votes) {
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  const int nu = t.cells[u] + 1, nv = t.cells[v] + 1, na = t.cells[axis] + 1;
  for (int64_t ray = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; ray < int64_t(nu) * nv;
       ray += int64_t(gridDim.x) * blockDim.x) {
    int n[3];
    n[u] = int(ray % nu);
    n[v] = int(ray / nu);
    n[axis] = 0;
    RayVoteCursor cursor = startRayVote(t, axis, n);
    for (int i = 0; i < na; ++i) {
      n[axis] = i;
      votes[tileNode(t, n[0], n[1], n[2])] += rayVote(t, axis, cursor, i);
    }
  }
}

// The node bit planes (tile_sides.h's layout): one thread per word of 64 nodes of a row.
__global__ void decideSides(TileView t, const uint8_t* votes, uint64_t* insideBits,
                            uint64_t* unanimousBits, unsigned long long* disagreements) {
  const int nx = t.cells[0] + 1, ny = t.cells[1] + 1, nz = t.cells[2] + 1;
  const int64_t total = t.rowWords * ny * nz;
  unsigned long long local = 0;
  for (int64_t w = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; w < total;
       w += int64_t(gridDim.x) * blockDim.x) {
    const int64_t row = w / t.rowWords;
    const int firstNode = int(w % t.rowWords) * 64;
    const int y = int(row % ny), z = int(row / ny);
    const bool rowFace = t.first[1] + y == 0 || t.first[2] + z == 0 ||
                         t.first[1] + y == t.globalCells[1] || t.first[2] + z == t.globalCells[2];
    uint64_t inside = 0, unanimous = 0;
    const int last = min(64, nx - firstNode);
    for (int b = 0; b < last; ++b) {
      const int x = firstNode + b, gx = t.first[0] + x;
      const uint8_t vote = votes[tileNode(t, x, y, z)];
      local += (vote == 1 || vote == 2) ? 1 : 0;
      const bool face = rowFace || gx == 0 || gx == t.globalCells[0];
      inside |= uint64_t(decideNodeSide(vote, face)) << b;
      unanimous |= uint64_t(vote == 0 || vote == 3) << b;
    }
    insideBits[w] = inside;
    unanimousBits[w] = unanimous;
  }
  if (local) atomicAdd(disagreements, local);
}

// One thread per cell: whether its corners are mixed; also counts the boundary cells (one
// atomic per block).
__global__ void boundaryFlags(TileView t, uint8_t* flags, unsigned long long* boundaryCount) {
  const int64_t total = int64_t(t.cells[0]) * t.cells[1] * t.cells[2];
  const int64_t c = blockIdx.x * int64_t(blockDim.x) + threadIdx.x;
  int flag = 0;
  if (c < total) {
    const int x = int(c % t.cells[0]), y = int((c / t.cells[0]) % t.cells[1]),
              z = int(c / (int64_t(t.cells[0]) * t.cells[1]));
    const uint8_t mask = cellMaskFromNodes(t, x, y, z);
    flag = (mask != 0 && mask != 255) ? 1 : 0;
    flags[c] = uint8_t(flag);
  }
  const int inBlock = __syncthreads_count(flag);
  if (threadIdx.x == 0 && inBlock) atomicAdd(boundaryCount, (unsigned long long)inBlock);
}

__global__ void boundaryMasks(TileView t, uint8_t* masks) {
  for (int64_t b = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; b < t.boundaryCount;
       b += int64_t(gridDim.x) * blockDim.x) {
    int c[3];
    tileCellCoords(t, t.boundary[b], c);
    masks[b] = cellMaskFromNodes(t, c[0], c[1], c[2]);
  }
}

__global__ void componentCounts(TileView t, uint32_t* counts) {
  for (int64_t b = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; b <= t.boundaryCount;
       b += int64_t(gridDim.x) * blockDim.x)
    counts[b] =
        b < t.boundaryCount ? uint32_t(c_cellCases.cases[t.boundaryMasks[b]].components) : 0u;
}

__global__ void placeVertices(TileView t, CellVertex* vertices) {
  for (int64_t b = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; b < t.boundaryCount;
       b += int64_t(gridDim.x) * blockDim.x)
    placeCellVertices(t, c_cellCases, b, vertices + t.vertexStart[b]);
}

__global__ void countPolygons(TileView t, uint32_t* triangles, uint32_t* faces) {
  for (int64_t b = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; b <= t.boundaryCount;
       b += int64_t(gridDim.x) * blockDim.x) {
    if (b == t.boundaryCount) {
      triangles[b] = faces[b] = 0;
      continue;
    }
    int faceCount = 0;  // from the corner signs, as the CPU counts them
    triangles[b] = uint32_t(cellPolygonCounts(t, c_cellCases, b, &faceCount));
    faces[b] = uint32_t(faceCount);
  }
}

__global__ void writePolygons(TileView t, const uint32_t* triangleStart, const uint32_t* faceStart,
                              CellTriangle* triangles, CellVertex* faces,
                              unsigned long long* synthesized) {
  unsigned long long local = 0;
  for (int64_t b = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; b < t.boundaryCount;
       b += int64_t(gridDim.x) * blockDim.x) {
    int faceCount = 0, synth = 0;
    cellPolygons(t, c_cellCases, b, triangles + triangleStart[b], faces + faceStart[b], &faceCount,
                 &synth);
    local += unsigned(synth);
  }
  if (local) atomicAdd(synthesized, local);
}

// In-place exclusive scan of count + 1 uint32 values; returns the total (one wait).
uint32_t scan32(uint32_t* data, int64_t count, const DeviceStream& stream) {
  size_t tempBytes = 0;
  STRATA_CUDA_CHECK(
      cub::DeviceScan::ExclusiveSum(nullptr, tempBytes, data, data, count + 1, stream.get()));
  DeviceBuffer<unsigned char> temp(tempBytes, stream);
  STRATA_CUDA_CHECK(
      cub::DeviceScan::ExclusiveSum(temp.data(), tempBytes, data, data, count + 1, stream.get()));
  uint32_t total = 0;
  STRATA_CUDA_CHECK(cudaMemcpyAsync(&total, data + count, sizeof(uint32_t), cudaMemcpyDeviceToHost,
                                    stream.get()));
  stream.synchronize();
  return total;
}

// The tile's device arrays, in the order the steps make them; t views them.
struct DeviceTile {
  TileView t{};
  int64_t nodes = 0, cells = 0;
  DeviceBuffer<unsigned long long> counters;  // disagreements, synthesised crossings
  DeviceBuffer<uint64_t> insideBits, unanimousBits;
  DeviceBuffer<uint32_t> boundary, vertexStart, cornerCrossings;
  DeviceBuffer<uint8_t> boundaryMasks;
  DeviceBuffer<CellVertex> vertices;
};

// Node sides: votes of the three axes (a byte per node, released once decided), then majority
// and the outer faces into the bit planes.
void decideNodeSides(DeviceTile& d, const DeviceStream& stream) {
  DeviceBuffer<uint8_t> votes(static_cast<size_t>(d.nodes), stream);
  STRATA_CUDA_CHECK(cudaMemsetAsync(votes.data(), 0, votes.bytes(), stream.get()));
  for (int axis = 0; axis < 3; ++axis) {
    const int64_t rays = int64_t(d.t.cells[(axis + 1) % 3] + 1) * (d.t.cells[(axis + 2) % 3] + 1);
    voteAxis<<<blocksFor(rays, 128), 128, 0, stream.get()>>>(d.t, axis, votes.data());
    STRATA_CUDA_CHECK(cudaGetLastError());
  }
  d.t.rowWords = nodeRowWords(d.t.cells[0]);
  const int64_t words = d.t.rowWords * (d.t.cells[1] + 1) * (d.t.cells[2] + 1);
  d.insideBits = DeviceBuffer<uint64_t>(static_cast<size_t>(words), stream);
  d.unanimousBits = DeviceBuffer<uint64_t>(static_cast<size_t>(words), stream);
  decideSides<<<blocksFor(words, 256), 256, 0, stream.get()>>>(
      d.t, votes.data(), d.insideBits.data(), d.unanimousBits.data(), d.counters.data());
  STRATA_CUDA_CHECK(cudaGetLastError());
  d.t.insideBits = d.insideBits.data();
  d.t.unanimousBits = d.unanimousBits.data();
}

// The boundary cells in increasing index and their masks (room for exactly those: they follow
// the surface, not the volume).
void findBoundaryCells(DeviceTile& d, const DeviceStream& stream) {
  DeviceBuffer<uint8_t> flags(static_cast<size_t>(d.cells), stream);
  DeviceBuffer<unsigned long long> flagged(1, stream);
  STRATA_CUDA_CHECK(cudaMemsetAsync(flagged.data(), 0, flagged.bytes(), stream.get()));
  boundaryFlags<<<blocksFor(d.cells, 256), 256, 0, stream.get()>>>(d.t, flags.data(),
                                                                   flagged.data());
  STRATA_CUDA_CHECK(cudaGetLastError());
  unsigned long long boundaryCount = 0;
  STRATA_CUDA_CHECK(cudaMemcpyAsync(&boundaryCount, flagged.data(), sizeof(boundaryCount),
                                    cudaMemcpyDeviceToHost, stream.get()));
  stream.synchronize();
  d.boundary = DeviceBuffer<uint32_t>(static_cast<size_t>(boundaryCount), stream);
  d.boundaryMasks = DeviceBuffer<uint8_t>(static_cast<size_t>(boundaryCount), stream);
  DeviceBuffer<int64_t> selected(1, stream);
  d.t.boundary = d.boundary.data();
  d.t.boundaryMasks = d.boundaryMasks.data();
  d.t.boundaryCount = int64_t(boundaryCount);
  if (boundaryCount > 0) {
    thrust::counting_iterator<uint32_t> indices(0);
    size_t tempBytes = 0;
    STRATA_CUDA_CHECK(cub::DeviceSelect::Flagged(nullptr, tempBytes, indices, flags.data(),
                                                 d.boundary.data(), selected.data(), d.cells,
                                                 stream.get()));
    DeviceBuffer<unsigned char> temp(tempBytes, stream);
    STRATA_CUDA_CHECK(cub::DeviceSelect::Flagged(temp.data(), tempBytes, indices, flags.data(),
                                                 d.boundary.data(), selected.data(), d.cells,
                                                 stream.get()));
    boundaryMasks<<<blocksFor(int64_t(boundaryCount), 256), 256, 0, stream.get()>>>(
        d.t, d.boundaryMasks.data());
    STRATA_CUDA_CHECK(cudaGetLastError());
  }
}

// One vertex per component of each boundary cell.
void placeTileVertices(DeviceTile& d, const DeviceStream& stream) {
  const int64_t boundaryCount = d.t.boundaryCount;
  d.vertexStart = DeviceBuffer<uint32_t>(static_cast<size_t>(boundaryCount) + 1, stream);
  componentCounts<<<blocksFor(boundaryCount + 1, 256), 256, 0, stream.get()>>>(
      d.t, d.vertexStart.data());
  STRATA_CUDA_CHECK(cudaGetLastError());
  const uint32_t vertexCount = scan32(d.vertexStart.data(), boundaryCount, stream);
  d.t.vertexStart = d.vertexStart.data();
  d.vertices = DeviceBuffer<CellVertex>(vertexCount, stream);
  // Each boundary cell's corner-0 crossings, written with its vertices, read by the polygons.
  d.cornerCrossings = DeviceBuffer<uint32_t>(static_cast<size_t>(boundaryCount) * 3, stream);
  d.t.cornerCrossings = d.cornerCrossings.data();
  if (boundaryCount > 0) {
    placeVertices<<<blocksFor(boundaryCount, 128), 128, 0, stream.get()>>>(d.t, d.vertices.data());
    STRATA_CUDA_CHECK(cudaGetLastError());
  }
  d.t.vertices = d.vertices.data();
}

// Polygons: count, scan, write; then everything back to the host into *out: cell vertices then
// face vertices (as the CPU orders them), triangles, and the counters.
void emitTilePolygons(DeviceTile& d, const DeviceStream& stream, TileContour* out) {
  const int64_t boundaryCount = d.t.boundaryCount;
  DeviceBuffer<uint32_t> triangleStart(static_cast<size_t>(boundaryCount) + 1, stream),
      faceStart(static_cast<size_t>(boundaryCount) + 1, stream);
  countPolygons<<<blocksFor(boundaryCount + 1, 128), 128, 0, stream.get()>>>(
      d.t, triangleStart.data(), faceStart.data());
  STRATA_CUDA_CHECK(cudaGetLastError());
  const uint32_t triangleCount = scan32(triangleStart.data(), boundaryCount, stream);
  const uint32_t faceCount = scan32(faceStart.data(), boundaryCount, stream);
  DeviceBuffer<CellTriangle> triangles(triangleCount, stream);
  DeviceBuffer<CellVertex> faces(faceCount, stream);
  if (boundaryCount > 0) {
    writePolygons<<<blocksFor(boundaryCount, 128), 128, 0, stream.get()>>>(
        d.t, triangleStart.data(), faceStart.data(), triangles.data(), faces.data(),
        d.counters.data() + 1);
    STRATA_CUDA_CHECK(cudaGetLastError());
  }
  // The cell vertices, then the face-segment vertices after them, in one host array.
  out->vertices.resize(d.vertices.size() + faces.size());
  if (d.vertices.size())
    STRATA_CUDA_CHECK(cudaMemcpyAsync(out->vertices.data(), d.vertices.data(), d.vertices.bytes(),
                                      cudaMemcpyDeviceToHost, stream.get()));
  if (faces.size())
    STRATA_CUDA_CHECK(cudaMemcpyAsync(out->vertices.data() + d.vertices.size(), faces.data(),
                                      faces.bytes(), cudaMemcpyDeviceToHost, stream.get()));
  triangles.downloadAsync(&out->triangles);
  unsigned long long stats[2] = {0, 0};
  STRATA_CUDA_CHECK(cudaMemcpyAsync(stats, d.counters.data(), sizeof(stats), cudaMemcpyDeviceToHost,
                                    stream.get()));
  stream.synchronize();
  out->signDisagreements = stats[0];
  out->synthesizedCrossings = stats[1];
}

}  // namespace

TileContour contourTileOnDevice(const DeviceLdi& ldi, const glm::ivec3& globalCells,
                                const glm::ivec3& begin, const glm::ivec3& end,
                                const DeviceStream& stream) {
  uploadCellCases(stream);
  const Grid& grid = ldi.grid();
  DeviceTile d;
  d.t = makeTileView(grid.first, grid.cells, globalCells, begin, end);
  for (int a = 0; a < 3; ++a) {
    d.t.offsets[a] = ldi.axes[a].offsets.data();
    d.t.surfels[a] = ldi.axes[a].surfels.data();
  }
  d.nodes = int64_t(grid.cells.x + 1) * (grid.cells.y + 1) * (grid.cells.z + 1);
  d.cells = int64_t(grid.cells.x) * grid.cells.y * grid.cells.z;
  d.counters = DeviceBuffer<unsigned long long>(2, stream);
  STRATA_CUDA_CHECK(cudaMemsetAsync(d.counters.data(), 0, d.counters.bytes(), stream.get()));
  decideNodeSides(d, stream);
  findBoundaryCells(d, stream);
  placeTileVertices(d, stream);
  TileContour out;
  emitTilePolygons(d, stream, &out);
  return out;
}

}  // namespace strata
