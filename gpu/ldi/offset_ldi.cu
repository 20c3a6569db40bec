#include <cmath>

#include "engine/ldi/offset_math.h"
#include "gpu/ldi/csr_build.cuh"
#include "gpu/ldi/offset_ldi.cuh"

namespace strata {
namespace {

// Layouts. The CPU keeps every per-node array x-fastest; a pass along x with one thread per
// line then has neighbouring threads a whole row apart in memory. So the device keeps the data
// of x passes y-fastest (the lattice's strides say which: every shared function reads through
// them) and moves between the two layouts with a tiled transpose: every pass reads and writes
// neighbouring addresses from neighbouring threads. The values, and so the bits, are the same.
OffsetLattice yFastest(OffsetLattice lat) {
  lat.stride[1] = 1;
  lat.stride[0] = lat.n[1];
  lat.stride[2] = lat.n[0] * lat.n[1];
  return lat;
}

__global__ void seedLines(OffsetLattice lat, int axis, const uint32_t* offsets,
                          const Surfel* surfels, float bandSquared, float* d, uint32_t* leaf,
                          uint8_t* inside) {
  const int64_t lines = lat.lineCount(axis), raysU = lat.n[(axis + 1) % 3];
  for (int64_t t = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; t < lines;
       t += int64_t(gridDim.x) * blockDim.x) {
    int64_t i, j;
    lat.lineCoords(axis, t, &i, &j);
    const int64_t ray = i + j * raysU, start = lat.lineStart(axis, i, j);
    const uint32_t from = offsets[ray];
    offsetSeedLine(surfels + from, int64_t(offsets[ray + 1]) - int64_t(from), lat.first[axis],
                   lat.n[axis], lat.stride[axis], bandSquared, d + start, leaf + start,
                   inside ? inside + start : nullptr);
  }
}

// Scratch of line t is at t + q * lines (interleaved: coalesced across threads).
__global__ void envelopeLines(OffsetLattice lat, int axis, const float* in, const uint32_t* inLeaf,
                              float* out, uint32_t* outLeaf, float bandSquared, bool onlySmaller,
                              int32_t* v, double* z) {
  const int64_t lines = lat.lineCount(axis);
  for (int64_t t = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; t < lines;
       t += int64_t(gridDim.x) * blockDim.x) {
    int64_t i, j;
    lat.lineCoords(axis, t, &i, &j);
    const int64_t start = lat.lineStart(axis, i, j), step = lat.stride[axis];
    offsetEnvelopeLine(in + start, inLeaf + start, step, out + start, outLeaf + start, step,
                       lat.n[axis], lat.first[axis], v + t, z + t, lines, bandSquared, onlySmaller);
  }
}

// Layout changes go through 32 x 32 tiles of shared memory: blocks of 32 x 8 threads, grid
// (x tiles, y tiles, z); each tile is read along the input's fast axis and written along the
// output's, so both are coalesced.
constexpr int kTile = 32;

dim3 tileBlocks(const OffsetLattice& lat) {
  return dim3(unsigned((lat.n[0] + kTile - 1) / kTile), unsigned((lat.n[1] + kTile - 1) / kTile),
              unsigned(lat.n[2]));
}

// The distances d and their leaves l (x-fastest when toYFastest, else y-fastest) copied to
// outD and outL in the other layout; with onlySmaller only where d is smaller
// than outD (the minimum of two samplings, as offsetEnvelopeLine's onlySmaller).
__global__ void transposeValues(OffsetLattice lat, bool toYFastest, const float* d,
                                const uint32_t* l, float* outD, uint32_t* outL, bool onlySmaller) {
  __shared__ float tileD[kTile][kTile + 1];
  __shared__ uint32_t tileL[kTile][kTile + 1];
  const int64_t nx = lat.n[0], ny = lat.n[1], z = blockIdx.z;
  const int64_t slab = z * nx * ny;
  const int64_t x0 = int64_t(blockIdx.x) * kTile, y0 = int64_t(blockIdx.y) * kTile;
  for (int r = threadIdx.y; r < kTile; r += blockDim.y) {
    const int64_t fast = (toYFastest ? x0 : y0) + threadIdx.x, slow = (toYFastest ? y0 : x0) + r;
    const int64_t nFast = toYFastest ? nx : ny, nSlow = toYFastest ? ny : nx;
    if (fast < nFast && slow < nSlow) {
      tileD[r][threadIdx.x] = d[slab + fast + slow * nFast];
      tileL[r][threadIdx.x] = l[slab + fast + slow * nFast];
    }
  }
  __syncthreads();
  for (int r = threadIdx.y; r < kTile; r += blockDim.y) {
    const int64_t fast = (toYFastest ? y0 : x0) + threadIdx.x, slow = (toYFastest ? x0 : y0) + r;
    const int64_t nFast = toYFastest ? ny : nx, nSlow = toYFastest ? nx : ny;
    if (fast < nFast && slow < nSlow) {
      const int64_t at = slab + fast + slow * nFast;
      const float value = tileD[threadIdx.x][r];
      if (onlySmaller && !(value < outD[at])) continue;
      outD[at] = value;
      outL[at] = tileL[threadIdx.x][r];
    }
  }
}

void transposeValues(const OffsetLattice& lat, bool toYFastest, const float* d, const uint32_t* l,
                     float* outD, uint32_t* outL, bool onlySmaller, cudaStream_t s) {
  transposeValues<<<tileBlocks(lat), dim3(kTile, 8), 0, s>>>(lat, toYFastest, d, l, outD, outL,
                                                             onlySmaller);
  STRATA_CUDA_CHECK(cudaGetLastError());
}

// The last step of the distance transform, through tiles: best = min(best, d) with its leaf
// (strictly smaller replaces, as the CPU's envelope with onlySmaller), then the signed distance
// from best and the inside flags, written in both layouts. best and bestLeaf are x-fastest and take
// the signed distance's x-fastest copy in sdX and the leaves in place; d, l and insideY are
// y-fastest, and d and l take the signed distances and leaves in place.
__global__ void finishDistances(OffsetLattice lat, const float* best, uint32_t* bestLeaf, float* d,
                                uint32_t* l, const uint8_t* insideY, float* sdX) {
  __shared__ float tileD[kTile][kTile + 1];
  __shared__ uint32_t tileL[kTile][kTile + 1];
  __shared__ uint8_t tileIn[kTile][kTile + 1];
  const int64_t nx = lat.n[0], ny = lat.n[1], z = blockIdx.z;
  const int64_t slab = z * nx * ny;
  const int64_t x0 = int64_t(blockIdx.x) * kTile, y0 = int64_t(blockIdx.y) * kTile;
  for (int r = threadIdx.y; r < kTile; r += blockDim.y) {  // read y-fastest
    const int64_t y = y0 + threadIdx.x, x = x0 + r;
    if (y < ny && x < nx) {
      const int64_t at = slab + y + x * ny;
      tileD[r][threadIdx.x] = d[at];
      tileL[r][threadIdx.x] = l[at];
      tileIn[r][threadIdx.x] = insideY[at];
    }
  }
  __syncthreads();
  for (int r = threadIdx.y; r < kTile; r += blockDim.y) {  // x-fastest
    const int64_t x = x0 + threadIdx.x, y = y0 + r;
    if (x < nx && y < ny) {
      const int64_t at = slab + x + y * nx;
      float b = best[at];
      uint32_t leaf = bestLeaf[at];
      const float other = tileD[threadIdx.x][r];
      if (other < b) {
        b = other;
        leaf = tileL[threadIdx.x][r];
      }
      const float sd = offsetSignedDistance(b, tileIn[threadIdx.x][r]);
      sdX[at] = sd;
      bestLeaf[at] = leaf;
      tileD[threadIdx.x][r] = sd;
      tileL[threadIdx.x][r] = leaf;
    }
  }
  __syncthreads();
  for (int r = threadIdx.y; r < kTile; r += blockDim.y) {  // write y-fastest
    const int64_t y = y0 + threadIdx.x, x = x0 + r;
    if (y < ny && x < nx) {
      const int64_t at = slab + y + x * ny;
      d[at] = tileD[r][threadIdx.x];
      l[at] = tileL[r][threadIdx.x];
    }
  }
}

// The per-node arrays as the rays of each axis read them: x rays from the y-fastest copies.
struct RayInputs {
  OffsetLattice lat[3];
  const float* sd[3];
  const uint32_t* leaf[3];
};

// Ray r of the concatenated space, read with neighbouring threads on neighbouring nodes.
__device__ void rayCoords(const RaySpace& space, const RayInputs& in, int64_t r, int* axis,
                          int64_t* i, int64_t* j) {
  *axis = space.axisOf(r);
  const int64_t t = r - space.base[*axis];
  in.lat[*axis].lineCoords(*axis, t, i, j);
}

__global__ void countRays(RayInputs in, RaySpace space, double offsetCells, uint64_t* wide) {
  for (int64_t r = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; r <= space.total();
       r += int64_t(gridDim.x) * blockDim.x) {
    if (r == space.total()) {
      wide[r] = 0;
      continue;
    }
    int axis;
    int64_t i, j;
    rayCoords(space, in, r, &axis, &i, &j);
    wide[space.rayOf(axis, int(i), int(j))] =
        offsetRayCount(in.lat[axis], in.sd[axis], axis, i, j, offsetCells);
  }
}

__global__ void writeRays(RayInputs in, RaySpace space, double offsetCells, const uint64_t* wide,
                          AxisSurfelTargets targets) {
  for (int64_t r = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; r < space.total();
       r += int64_t(gridDim.x) * blockDim.x) {
    int axis;
    int64_t i, j;
    rayCoords(space, in, r, &axis, &i, &j);
    const int64_t ray = space.rayOf(axis, int(i), int(j));
    if (wide[ray + 1] == wide[ray]) continue;  // no crossing: nothing to write
    offsetWriteRay(in.lat[axis], in.sd[axis], in.leaf[axis], axis, i, j, offsetCells,
                   targets.surfels[axis] + (wide[ray] - wide[space.base[axis]]));
  }
}

constexpr unsigned kThreads = 256;

}  // namespace

std::shared_ptr<DeviceLdi> offsetOnDevice(const DeviceLdi& whole, double distance,
                                          const DeviceStream& stream) {
  if (!whole.whole()) throw Error("internal: offsetOnDevice needs every axis whole");
  if (!std::isfinite(distance)) throw Error("offset distance is not a finite number");
  const Grid& g = whole.grid();
  const int cells[3] = {g.cells.x, g.cells.y, g.cells.z};
  const int first[3] = {g.first.x, g.first.y, g.first.z};
  const OffsetLattice lat = makeOffsetLattice(cells, first);
  const double offsetCells = distance / g.h;
  const size_t count = static_cast<size_t>(lat.count);
  cudaStream_t s = stream.get();

  // Steps 1 and 2, as the CPU (offset_ldi.cpp): best = min(Ey(min(Ez Sx, Ex Sz)), Ez Ex Sy),
  // the same five envelopes in the same order. Passes along x run on the y-fastest layout,
  // along y on the x-fastest one, along z on either (z is the slowest axis of both); the x rays
  // seed on the y-fastest layout, the y rays on the x-fastest one, the z rays on either.
  const OffsetLattice latY = yFastest(lat);
  const float band = offsetBandSquared(offsetCells);
  DeviceBuffer<float> best(count, stream), da(count, stream), db(count, stream);
  DeviceBuffer<uint32_t> bestLeaf(count, stream), la(count, stream), lb(count, stream);
  DeviceBuffer<uint8_t> insideY(count, stream);  // y-fastest
  {
    DeviceBuffer<int32_t> v(count, stream);
    DeviceBuffer<double> z(count, stream);
    auto seed = [&](const OffsetLattice& on, int axis, float* d, uint32_t* l, uint8_t* in) {
      seedLines<<<blocksFor(lat.lineCount(axis), kThreads), kThreads, 0, s>>>(
          on, axis, whole.axes[axis].offsets.data(), whole.axes[axis].surfels.data(), band, d, l,
          in);
      STRATA_CUDA_CHECK(cudaGetLastError());
    };
    auto envelope = [&](const OffsetLattice& on, int axis, const float* d, const uint32_t* l,
                        float* out, uint32_t* outL, bool onlySmaller) {
      envelopeLines<<<blocksFor(lat.lineCount(axis), kThreads), kThreads, 0, s>>>(
          on, axis, d, l, out, outL, band, onlySmaller, v.data(), z.data());
      STRATA_CUDA_CHECK(cudaGetLastError());
    };
    // db = Ez Sx (y-fastest); the inside flags from the x rays.
    seed(latY, 0, da.data(), la.data(), insideY.data());
    envelope(latY, 2, da.data(), la.data(), db.data(), lb.data(), false);
    // db = min(db, Ex Sz); best = Ey db (x-fastest).
    seed(latY, 2, da.data(), la.data(), nullptr);
    envelope(latY, 0, da.data(), la.data(), db.data(), lb.data(), true);
    transposeValues(lat, false, db.data(), lb.data(), da.data(), la.data(), false, s);
    envelope(lat, 1, da.data(), la.data(), best.data(), bestLeaf.data(), false);
    // best = min(best, Ez Ex Sy).
    seed(lat, 1, da.data(), la.data(), nullptr);
    transposeValues(lat, true, da.data(), la.data(), db.data(), lb.data(), false, s);
    envelope(latY, 0, db.data(), lb.data(), da.data(), la.data(), false);
    envelope(latY, 2, da.data(), la.data(), db.data(), lb.data(), false);
  }
  // best = min(best, db), then the signed distances: into da (x-fastest) and db (y-fastest),
  // the leaves into bestLeaf and lb.
  finishDistances<<<tileBlocks(lat), dim3(kTile, 8), 0, s>>>(
      lat, best.data(), bestLeaf.data(), db.data(), lb.data(), insideY.data(), da.data());
  STRATA_CUDA_CHECK(cudaGetLastError());
  best.reset();
  la.reset();
  insideY.reset();

  // Step 3: count each ray's crossings, scan, allocate, write.
  RayInputs in;
  for (int a = 0; a < 3; ++a) {
    in.lat[a] = a == 0 ? latY : lat;
    in.sd[a] = a == 0 ? db.data() : da.data();
    in.leaf[a] = a == 0 ? lb.data() : bestLeaf.data();
  }
  auto out = std::make_shared<DeviceLdi>(g, stream);
  const RaySpace space(g);
  DeviceBuffer<uint64_t> wide(static_cast<size_t>(space.total()) + 1, stream);
  countRays<<<blocksFor(space.total() + 1, kThreads), kThreads, 0, s>>>(in, space, offsetCells,
                                                                        wide.data());
  STRATA_CUDA_CHECK(cudaGetLastError());
  exclusiveScanAsync(wide.data(), space.total() + 1, stream);
  const AxisSurfelTargets targets = allocateAxes(space, wide.data(), out.get(), "the offset");
  if (targets.total > 0) {
    writeRays<<<blocksFor(space.total(), kThreads), kThreads, 0, s>>>(in, space, offsetCells,
                                                                      wide.data(), targets);
    STRATA_CUDA_CHECK(cudaGetLastError());
  }
  stream.synchronize();
  return out;
}

}  // namespace strata
