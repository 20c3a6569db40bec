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

// The window coordinates (i, j) of line t along `axis`, numbered so that neighbouring threads
// take neighbouring nodes: i (on u) fastest, except along y in the x-fastest layout (u = z).
__device__ void lineCoords(const OffsetLattice& lat, int axis, int64_t t, int64_t* i, int64_t* j) {
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  if (lat.stride[v] < lat.stride[u]) {
    *j = t % lat.n[v];
    *i = t / lat.n[v];
  } else {
    *i = t % lat.n[u];
    *j = t / lat.n[u];
  }
}

__global__ void seedLines(OffsetLattice lat, int axis, const uint32_t* offsets,
                          const Surfel* surfels, float* d, uint32_t* leaf, uint8_t* inside) {
  const int64_t lines = lat.lineCount(axis), raysU = lat.n[(axis + 1) % 3];
  for (int64_t t = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; t < lines;
       t += int64_t(gridDim.x) * blockDim.x) {
    int64_t i, j;
    lineCoords(lat, axis, t, &i, &j);
    const int64_t ray = i + j * raysU, start = lat.lineStart(axis, i, j);
    const uint32_t from = offsets[ray];
    offsetSeedLine(surfels + from, int64_t(offsets[ray + 1]) - int64_t(from), lat.first[axis],
                   lat.n[axis], lat.stride[axis], d + start, leaf + start,
                   inside ? inside + start : nullptr);
  }
}

// Scratch of line t is at t + q * lines (interleaved: coalesced across threads).
__global__ void envelopeLines(OffsetLattice lat, int axis, const float* in, const uint32_t* inLeaf,
                              float* out, uint32_t* outLeaf, int32_t* v, double* z) {
  const int64_t lines = lat.lineCount(axis);
  for (int64_t t = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; t < lines;
       t += int64_t(gridDim.x) * blockDim.x) {
    int64_t i, j;
    lineCoords(lat, axis, t, &i, &j);
    const int64_t start = lat.lineStart(axis, i, j), step = lat.stride[axis];
    offsetEnvelopeLine(in + start, inLeaf + start, step, out + start, outLeaf + start, step,
                       lat.n[axis], v + t, z + t, lines);
  }
}

// Copies `in` (x-fastest when toYFastest, else y-fastest) to `out` in the other layout, through
// 32 x 32 tiles of shared memory. Blocks of 32 x 8 threads; grid (x tiles, y tiles, z).
constexpr int kTile = 32;
template <typename T>
__global__ void transposeXY(OffsetLattice lat, bool toYFastest, const T* in, T* out) {
  __shared__ T tile[kTile][kTile + 1];
  const int64_t nx = lat.n[0], ny = lat.n[1], z = blockIdx.z;
  const int64_t slab = z * nx * ny;
  const int64_t x0 = int64_t(blockIdx.x) * kTile, y0 = int64_t(blockIdx.y) * kTile;
  // Read: along the input's fast axis.
  for (int r = threadIdx.y; r < kTile; r += blockDim.y) {
    const int64_t fast = (toYFastest ? x0 : y0) + threadIdx.x, slow = (toYFastest ? y0 : x0) + r;
    const int64_t nFast = toYFastest ? nx : ny, nSlow = toYFastest ? ny : nx;
    if (fast < nFast && slow < nSlow) tile[r][threadIdx.x] = in[slab + fast + slow * nFast];
  }
  __syncthreads();
  // Write: along the output's fast axis (the input's slow one).
  for (int r = threadIdx.y; r < kTile; r += blockDim.y) {
    const int64_t fast = (toYFastest ? y0 : x0) + threadIdx.x, slow = (toYFastest ? x0 : y0) + r;
    const int64_t nFast = toYFastest ? ny : nx, nSlow = toYFastest ? nx : ny;
    if (fast < nFast && slow < nSlow) out[slab + fast + slow * nFast] = tile[threadIdx.x][r];
  }
}

template <typename T>
void transpose(const OffsetLattice& lat, bool toYFastest, const T* in, T* out, cudaStream_t s) {
  const dim3 blocks(unsigned((lat.n[0] + kTile - 1) / kTile),
                    unsigned((lat.n[1] + kTile - 1) / kTile), unsigned(lat.n[2]));
  transposeXY<T><<<blocks, dim3(kTile, 8), 0, s>>>(lat, toYFastest, in, out);
  STRATA_CUDA_CHECK(cudaGetLastError());
}

// best = min(best, d) with its leaf (best = d on the first axis).
__global__ void keepSmaller(int64_t count, bool first, const float* d, const uint32_t* leaf,
                            float* best, uint32_t* bestLeaf) {
  for (int64_t i = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; i < count;
       i += int64_t(gridDim.x) * blockDim.x)
    if (first || d[i] < best[i]) {
      best[i] = d[i];
      bestLeaf[i] = leaf[i];
    }
}

__global__ void signedDistances(int64_t count, const float* best, const uint8_t* inside,
                                float* sd) {
  for (int64_t i = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; i < count;
       i += int64_t(gridDim.x) * blockDim.x)
    sd[i] = offsetSignedDistance(best[i], inside[i]);
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
  lineCoords(in.lat[*axis], *axis, t, i, j);
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

  // Steps 1 and 2, as the CPU: seed along each axis, envelope along the two others in the same
  // order, keep the smallest. Buffers A and B (distance and leaf) take turns as input and output;
  // passes along x run on the y-fastest layout.
  const OffsetLattice latY = yFastest(lat);
  DeviceBuffer<float> best(count, stream), da(count, stream), db(count, stream);
  DeviceBuffer<uint32_t> bestLeaf(count, stream), la(count, stream), lb(count, stream);
  DeviceBuffer<uint8_t> inside(count, stream);
  {
    DeviceBuffer<int32_t> v(count, stream);
    DeviceBuffer<double> z(count, stream);  // also the inside flags' y-fastest copy
    float* d[2] = {da.data(), db.data()};
    uint32_t* l[2] = {la.data(), lb.data()};
    int cur = 0;  // the buffer holding the current values
    auto swapTo = [&](bool toYFastest) {
      transpose(lat, toYFastest, d[cur], d[1 - cur], s);
      transpose(lat, toYFastest, l[cur], l[1 - cur], s);
      cur = 1 - cur;
    };
    auto envelope = [&](int axis) {
      const OffsetLattice& on = axis == 0 ? latY : lat;
      if (axis == 0) swapTo(true);
      envelopeLines<<<blocksFor(lat.lineCount(axis), kThreads), kThreads, 0, s>>>(
          on, axis, d[cur], l[cur], d[1 - cur], l[1 - cur], v.data(), z.data());
      STRATA_CUDA_CHECK(cudaGetLastError());
      cur = 1 - cur;
      if (axis == 0) swapTo(false);
    };
    for (int axis = 0; axis < 3; ++axis) {
      const DeviceAxisLdi& a = whole.axes[axis];
      const OffsetLattice& on = axis == 0 ? latY : lat;
      uint8_t* insideHere = axis == 0 ? reinterpret_cast<uint8_t*>(z.data()) : nullptr;
      seedLines<<<blocksFor(lat.lineCount(axis), kThreads), kThreads, 0, s>>>(
          on, axis, a.offsets.data(), a.surfels.data(), d[cur], l[cur], insideHere);
      STRATA_CUDA_CHECK(cudaGetLastError());
      if (axis == 0) {
        transpose(lat, false, insideHere, inside.data(), s);
        swapTo(false);
      }
      envelope((axis + 1) % 3);
      envelope((axis + 2) % 3);
      keepSmaller<<<blocksFor(lat.count, kThreads), kThreads, 0, s>>>(
          lat.count, axis == 0, d[cur], l[cur], best.data(), bestLeaf.data());
      STRATA_CUDA_CHECK(cudaGetLastError());
    }
  }
  // Signed distances in da (x-fastest) and db (y-fastest), the leaves in bestLeaf and lb.
  signedDistances<<<blocksFor(lat.count, kThreads), kThreads, 0, s>>>(lat.count, best.data(),
                                                                      inside.data(), da.data());
  STRATA_CUDA_CHECK(cudaGetLastError());
  transpose(lat, true, da.data(), db.data(), s);
  transpose(lat, true, bestLeaf.data(), lb.data(), s);
  best.reset();
  la.reset();
  inside.reset();

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
