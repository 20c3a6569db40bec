#include <cub/device/device_scan.cuh>

#include <string>

#include "gpu/ldi/csr_build.cuh"

#include "engine/util/error.h"

namespace strata {
namespace {

__global__ void widenKernel(const uint32_t* counts, int64_t total, uint64_t* wide) {
  for (int64_t r = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; r <= total;
       r += int64_t(gridDim.x) * blockDim.x)
    wide[r] = r < total ? counts[r] : 0;
}

// Axis a's offsets relative to the axis's first surfel.
__global__ void axisOffsets(const uint64_t* wide, int64_t first, int64_t rays, uint32_t* out) {
  for (int64_t r = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; r <= rays;
       r += int64_t(gridDim.x) * blockDim.x)
    out[r] = uint32_t(wide[first + r] - wide[first]);
}

// One axis of one LDI of a batch: its rays' place among the concatenated rays, and where its
// offsets and surfels go.
struct AxisSegment {
  int64_t first;  // first global ray
  int64_t rays;
  uint32_t* offsets;  // rays + 1
  Surfel* surfels;
};

// The segment holding global ray r: the last whose first ray is <= r (a segment without rays
// shares its first ray with the next, which comes after it).
__device__ int segmentOf(const AxisSegment* segments, int count, int64_t r) {
  int lo = 0, hi = count;  // segments[lo].first <= r < segments[hi].first
  while (hi - lo > 1) {
    const int mid = (lo + hi) / 2;
    if (segments[mid].first <= r)
      lo = mid;
    else
      hi = mid;
  }
  return lo;
}

// Every ray's offset and list, copied into its segment's axis.
__global__ void copySegmentRays(const AxisSegment* segments, int segmentCount, int64_t total,
                                const uint64_t* wide, const uint32_t* counts, const Surfel* scratch,
                                const uint64_t* scratchOffsets) {
  for (int64_t r = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; r < total;
       r += int64_t(gridDim.x) * blockDim.x) {
    const AxisSegment& s = segments[segmentOf(segments, segmentCount, r)];
    const uint64_t at = wide[r] - wide[s.first];
    s.offsets[r - s.first] = uint32_t(at);
    if (counts[r] == 0) continue;
    const Surfel* from = scratch + scratchOffsets[r];
    for (uint32_t k = 0; k < counts[r]; ++k) s.surfels[at + k] = from[k];
  }
}

// Each segment's closing offset (its surfel count).
__global__ void closeSegments(const AxisSegment* segments, int segmentCount, const uint64_t* wide) {
  for (int k = blockIdx.x * blockDim.x + threadIdx.x; k < segmentCount; k += gridDim.x * blockDim.x)
    segments[k].offsets[segments[k].rays] =
        uint32_t(wide[segments[k].first + segments[k].rays] - wide[segments[k].first]);
}

// values[k] = wide[at[k]].
__global__ void gatherValues(const uint64_t* wide, const int64_t* at, int n, uint64_t* values) {
  for (int k = blockIdx.x * blockDim.x + threadIdx.x; k < n; k += gridDim.x * blockDim.x)
    values[k] = wide[at[k]];
}

// Per grid ray of one axis: its surfel count in a windowed axis (0 outside the window), widened;
// wide[rays] = 0.
__global__ void windowCounts(const uint32_t* offsets, RayWindow window, int raysU, int64_t rays,
                             uint64_t* wide) {
  for (int64_t r = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; r <= rays;
       r += int64_t(gridDim.x) * blockDim.x) {
    uint64_t n = 0;
    if (r < rays) {
      const int i = int(r % raysU), j = int(r / raysU);
      if (i >= window.u0 && j >= window.v0 && i < window.u0 + window.uCount &&
          j < window.v0 + window.vCount) {
        const int64_t local = int64_t(i - window.u0) + int64_t(j - window.v0) * window.uCount;
        n = offsets[local + 1] - offsets[local];
      }
    }
    wide[r] = n;
  }
}

// The source ray of ray r of a window of `axis` (raysU across; ray (i, j) is ray
// i + shift.di + (j + shift.dj) * fromU of the LDI's fromU x fromV rays), or -1 where the LDI
// has no such ray (a window reaching beyond it: rewindowLdi's empty rays).
__device__ int64_t sourceRay(int64_t r, RayShift shift, int fromU, int fromV, int raysU) {
  const int64_t i = r % raysU + shift.di, j = r / raysU + shift.dj;
  return i < 0 || j < 0 || i >= fromU || j >= fromV ? -1 : i + j * int64_t(fromU);
}

// Per ray of the window: its surfel count, widened; wide[rays] = 0 (cropLdi's counts).
__global__ void cropCounts(const uint32_t* offsets, RayShift shift, int fromU, int fromV, int raysU,
                           int64_t rays, uint64_t* wide) {
  for (int64_t r = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; r <= rays;
       r += int64_t(gridDim.x) * blockDim.x) {
    uint64_t n = 0;
    if (r < rays) {
      const int64_t from = sourceRay(r, shift, fromU, fromV, raysU);
      if (from >= 0) n = offsets[from + 1] - offsets[from];
    }
    wide[r] = n;
  }
}

// Each window ray's list copied to its place (wide: the scanned counts).
__global__ void cropCopy(const uint32_t* offsets, const Surfel* surfels, RayShift shift, int fromU,
                         int fromV, int raysU, int64_t rays, const uint64_t* wide, Surfel* out) {
  for (int64_t r = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; r < rays;
       r += int64_t(gridDim.x) * blockDim.x) {
    const int64_t from = sourceRay(r, shift, fromU, fromV, raysU);
    if (from < 0) continue;
    const Surfel* in = surfels + offsets[from];
    const uint32_t n = offsets[from + 1] - offsets[from];
    for (uint32_t k = 0; k < n; ++k) out[wide[r] + k] = in[k];
  }
}

template <typename T>
DeviceBuffer<T> copyOf(const DeviceBuffer<T>& from, const DeviceStream& stream) {
  DeviceBuffer<T> to(from.size(), stream);
  if (from.size())
    STRATA_CUDA_CHECK(cudaMemcpyAsync(to.data(), from.data(), from.bytes(),
                                      cudaMemcpyDeviceToDevice, stream.get()));
  return to;
}

}  // namespace

std::shared_ptr<const DeviceLdi> wholeOnDevice(const std::shared_ptr<const DeviceLdi>& ldi,
                                               const DeviceStream& stream) {
  if (ldi->whole()) return ldi;
  const Grid& grid = ldi->grid();
  auto out = std::make_shared<DeviceLdi>(grid, stream);
  for (int a = 0; a < 3; ++a) {
    const DeviceAxisLdi& from = ldi->axes[a];
    DeviceAxisLdi& to = out->axes[a];
    // Window rays keep their order in the grid's (both row by row), so the surfels do too.
    to.surfels = copyOf(from.surfels, stream);
    if (from.whole) {
      to.offsets = copyOf(from.offsets, stream);
      continue;
    }
    const int64_t rays = grid.rayCount(a);
    DeviceBuffer<uint64_t> wide(static_cast<size_t>(rays) + 1, stream);
    windowCounts<<<blocksFor(rays + 1, 256), 256, 0, stream.get()>>>(
        from.offsets.data(), from.window, grid.raysU(a), rays, wide.data());
    STRATA_CUDA_CHECK(cudaGetLastError());
    exclusiveScanAsync(wide.data(), rays + 1, stream);
    to.offsets = DeviceBuffer<uint32_t>(static_cast<size_t>(rays) + 1, stream);
    axisOffsets<<<blocksFor(rays + 1, 256), 256, 0, stream.get()>>>(wide.data(), 0, rays,
                                                                    to.offsets.data());
    STRATA_CUDA_CHECK(cudaGetLastError());
  }
  stream.synchronize();
  return out;
}

namespace {
// The rays of `window` (on ldi's lattice) with their lists from `ldi`, empty where it has none.
std::shared_ptr<const DeviceLdi> copyWindowRays(const std::shared_ptr<const DeviceLdi>& ldi,
                                                const Grid& window, const RayShift shifts[3],
                                                const DeviceStream& stream) {
  const std::shared_ptr<const DeviceLdi> whole = wholeOnDevice(ldi, stream);
  auto out = std::make_shared<DeviceLdi>(window, stream);
  DeviceBuffer<uint64_t> wide[3];
  int64_t rays[3];
  const Grid& from = ldi->grid();
  for (int a = 0; a < 3; ++a) {
    const RayShift shift = shifts[a];
    rays[a] = window.rayCount(a);
    wide[a] = DeviceBuffer<uint64_t>(static_cast<size_t>(rays[a]) + 1, stream);
    cropCounts<<<blocksFor(rays[a] + 1, 256), 256, 0, stream.get()>>>(
        whole->axes[a].offsets.data(), shift, from.raysU(a), from.raysV(a), window.raysU(a),
        rays[a], wide[a].data());
    STRATA_CUDA_CHECK(cudaGetLastError());
    exclusiveScanAsync(wide[a].data(), rays[a] + 1, stream);
  }
  const uint64_t* at[3] = {wide[0].data() + rays[0], wide[1].data() + rays[1],
                           wide[2].data() + rays[2]};
  uint64_t totals[3];
  readBack(at, totals, 3, stream);
  for (int a = 0; a < 3; ++a) {
    checkSurfelCount(totals[a], "a cropped LDI");
    const RayShift shift = shifts[a];
    DeviceAxisLdi& to = out->axes[a];
    to.offsets = DeviceBuffer<uint32_t>(static_cast<size_t>(rays[a]) + 1, stream);
    axisOffsets<<<blocksFor(rays[a] + 1, 256), 256, 0, stream.get()>>>(wide[a].data(), 0, rays[a],
                                                                       to.offsets.data());
    STRATA_CUDA_CHECK(cudaGetLastError());
    to.surfels = DeviceBuffer<Surfel>(static_cast<size_t>(totals[a]), stream);
    if (rays[a] > 0 && totals[a] > 0) {
      cropCopy<<<blocksFor(rays[a], 256), 256, 0, stream.get()>>>(
          whole->axes[a].offsets.data(), whole->axes[a].surfels.data(), shift, from.raysU(a),
          from.raysV(a), window.raysU(a), rays[a], wide[a].data(), to.surfels.data());
      STRATA_CUDA_CHECK(cudaGetLastError());
    }
  }
  stream.synchronize();
  return out;
}
}  // namespace

std::shared_ptr<const DeviceLdi> cropOnDevice(const std::shared_ptr<const DeviceLdi>& ldi,
                                              const Grid& window, const DeviceStream& stream) {
  RayShift shifts[3];
  for (int a = 0; a < 3; ++a) shifts[a] = rayShift(ldi->grid(), window, a);  // throws if outside
  return copyWindowRays(ldi, window, shifts, stream);
}

std::shared_ptr<const DeviceLdi> rewindowOnDevice(const std::shared_ptr<const DeviceLdi>& ldi,
                                                  const Grid& window, const DeviceStream& stream) {
  const Grid& from = ldi->grid();
  if (window.h != from.h || window.origin != from.origin)
    throw Error("rewindowing an LDI to a window of another lattice");
  RayShift shifts[3];
  for (int a = 0; a < 3; ++a) {
    const int u = (a + 1) % 3, v = (a + 2) % 3;
    shifts[a] = RayShift{window.first[u] - from.first[u], window.first[v] - from.first[v]};
  }
  return copyWindowRays(ldi, window, shifts, stream);
}

void exclusiveScanAsync(uint64_t* data, int64_t count, const DeviceStream& stream) {
  size_t tempBytes = 0;
  STRATA_CUDA_CHECK(
      cub::DeviceScan::ExclusiveSum(nullptr, tempBytes, data, data, count, stream.get()));
  DeviceBuffer<unsigned char> temp(tempBytes, stream);
  STRATA_CUDA_CHECK(
      cub::DeviceScan::ExclusiveSum(temp.data(), tempBytes, data, data, count, stream.get()));
}

void readBack(const uint64_t* const* addresses, uint64_t* values, int n,
              const DeviceStream& stream) {
  for (int i = 0; i < n; ++i)
    STRATA_CUDA_CHECK(cudaMemcpyAsync(values + i, addresses[i], sizeof(uint64_t),
                                      cudaMemcpyDeviceToHost, stream.get()));
  stream.synchronize();
}

void widenCounts(const uint32_t* counts, int64_t total, uint64_t* wide,
                 const DeviceStream& stream) {
  widenKernel<<<blocksFor(total + 1, 256), 256, 0, stream.get()>>>(counts, total, wide);
  STRATA_CUDA_CHECK(cudaGetLastError());
}

AxisSurfelTargets allocateAxes(const RaySpace& space, const uint64_t* wide, DeviceLdi* out,
                               const char* what) {
  const DeviceStream& stream = out->stream();
  const uint64_t* at[4] = {wide + space.base[0], wide + space.base[1], wide + space.base[2],
                           wide + space.base[3]};
  uint64_t starts[4];
  readBack(at, starts, 4, stream);
  AxisSurfelTargets targets;
  targets.total = starts[3];
  for (int a = 0; a < 3; ++a) {
    const uint64_t n = starts[a + 1] - starts[a];
    checkSurfelCount(n, what);
    const int64_t rays = space.base[a + 1] - space.base[a];
    DeviceAxisLdi& axis = out->axes[a];
    axis.offsets = DeviceBuffer<uint32_t>(static_cast<size_t>(rays) + 1, stream);
    axisOffsets<<<blocksFor(rays + 1, 256), 256, 0, stream.get()>>>(wide, space.base[a], rays,
                                                                    axis.offsets.data());
    STRATA_CUDA_CHECK(cudaGetLastError());
    axis.surfels = DeviceBuffer<Surfel>(static_cast<size_t>(n), stream);
    targets.surfels[a] = axis.surfels.data();
  }
  return targets;
}

void buildAxes(const RaySpace& space, const uint32_t* counts, const Surfel* scratch,
               const uint64_t* scratchOffsets, DeviceLdi* out, const char* what) {
  RaySpaces spaces;
  spaces.add(space);
  buildAxesOfMany(spaces, counts, scratch, scratchOffsets, {out}, what);
}

void buildAxesOfMany(const RaySpaces& spaces, const uint32_t* counts, const Surfel* scratch,
                     const uint64_t* scratchOffsets, const std::vector<DeviceLdi*>& outs,
                     const char* what) {
  if (outs.empty()) return;
  const DeviceStream& stream = outs[0]->stream();
  const int64_t total = spaces.total;
  DeviceBuffer<uint64_t> wide(static_cast<size_t>(total) + 1, stream);
  widenCounts(counts, total, wide.data(), stream);
  exclusiveScanAsync(wide.data(), total + 1, stream);

  // Each axis's first ray, and the end: their scanned values are the axes' surfel starts.
  std::vector<AxisSegment> segments;
  std::vector<int64_t> at;
  for (size_t k = 0; k < outs.size(); ++k)
    for (int a = 0; a < 3; ++a) {
      const RaySpace& space = spaces.spaces[k];
      const int64_t first = spaces.first[k] + space.base[a];
      segments.push_back(AxisSegment{first, space.base[a + 1] - space.base[a], nullptr, nullptr});
      at.push_back(first);
    }
  at.push_back(total);
  const auto deviceAt = DeviceBuffer<int64_t>::upload(at, stream);
  DeviceBuffer<uint64_t> deviceStarts(at.size(), stream);
  gatherValues<<<blocksFor(int64_t(at.size()), 128), 128, 0, stream.get()>>>(
      wide.data(), deviceAt.data(), int(at.size()), deviceStarts.data());
  STRATA_CUDA_CHECK(cudaGetLastError());
  std::vector<uint64_t> starts;
  deviceStarts.downloadAsync(&starts);
  stream.synchronize();

  for (size_t k = 0; k < outs.size(); ++k)
    for (int a = 0; a < 3; ++a) {
      AxisSegment& s = segments[3 * k + size_t(a)];
      const uint64_t n = starts[3 * k + size_t(a) + 1] - starts[3 * k + size_t(a)];
      checkSurfelCount(n, what);
      DeviceAxisLdi& axis = outs[k]->axes[a];
      axis.offsets = DeviceBuffer<uint32_t>(static_cast<size_t>(s.rays) + 1, stream);
      axis.surfels = DeviceBuffer<Surfel>(static_cast<size_t>(n), stream);
      s.offsets = axis.offsets.data();
      s.surfels = axis.surfels.data();
    }
  const auto deviceSegments = DeviceBuffer<AxisSegment>::upload(segments, stream);
  const int segmentCount = int(segments.size());
  if (total > 0) {
    copySegmentRays<<<blocksFor(total, 256), 256, 0, stream.get()>>>(
        deviceSegments.data(), segmentCount, total, wide.data(), counts, scratch, scratchOffsets);
    STRATA_CUDA_CHECK(cudaGetLastError());
  }
  closeSegments<<<blocksFor(segmentCount, 128), 128, 0, stream.get()>>>(deviceSegments.data(),
                                                                        segmentCount, wide.data());
  STRATA_CUDA_CHECK(cudaGetLastError());
}

}  // namespace strata
