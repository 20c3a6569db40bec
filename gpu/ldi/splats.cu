#include "gpu/ldi/csr_build.cuh"
#include "gpu/ldi/splats.cuh"

namespace strata {
namespace {

struct AxisSurfels {
  const uint32_t* offsets[3];
  const Surfel* surfels[3];
};

// The index of global ray R (R over the three axes' concatenated rays) in the level-major order
// of buildSplats: block kSplatLevels - 1 - level of `total` entries, then R.
__device__ int64_t slotOf(const RaySpace& space, const SplatFrame& frame, int64_t r) {
  const int axis = space.axisOf(r);
  const int level = splatRayLevel(frame, axis, r - space.base[axis]);
  return int64_t(kSplatLevels - 1 - level) * space.total() + r;
}

// counts[slotOf(R)] = splats on global ray R (the other blocks' entries of R stay 0).
__global__ void countSplats(RaySpace space, AxisSurfels in, SplatFrame frame, uint64_t* counts) {
  for (int64_t r = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; r < space.total();
       r += int64_t(gridDim.x) * blockDim.x) {
    const int axis = space.axisOf(r);
    const int64_t ray = r - space.base[axis];
    uint64_t n = 0;
    for (uint32_t k = in.offsets[axis][ray]; k < in.offsets[axis][ray + 1]; ++k)
      n += surfelMakesSplat(in.surfels[axis][k], axis) ? 1 : 0;
    counts[slotOf(space, frame, r)] = n;
  }
}

__global__ void writeSplats(RaySpace space, AxisSurfels in, SplatFrame frame,
                            const uint64_t* starts, Splat* out) {
  for (int64_t r = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; r < space.total();
       r += int64_t(gridDim.x) * blockDim.x) {
    const int axis = space.axisOf(r);
    const int64_t ray = r - space.base[axis];
    uint64_t at = starts[slotOf(space, frame, r)];
    for (uint32_t k = in.offsets[axis][ray]; k < in.offsets[axis][ray + 1]; ++k) {
      const Surfel s = in.surfels[axis][k];
      if (surfelMakesSplat(s, axis)) out[at++] = splatOf(frame, axis, ray, s);
    }
  }
}

}  // namespace

void DeviceSplats::copyToHost(Splat* out) const {
  if (!splats_.size()) return;
  STRATA_CUDA_CHECK(cudaMemcpyAsync(out, splats_.data(), splats_.bytes(), cudaMemcpyDeviceToHost,
                                    stream().get()));
  stream().synchronize();
}

std::shared_ptr<DeviceSplats> splatsOnDevice(const DeviceLdi& ldi, const DeviceStream& stream) {
  const RaySpace space(ldi.grid());
  const int64_t total = space.total();
  AxisSurfels in;
  for (int a = 0; a < 3; ++a) {
    in.offsets[a] = ldi.axes[a].offsets.data();
    in.surfels[a] = ldi.axes[a].surfels.data();
  }
  const SplatFrame frame = splatFrame(ldi.grid());
  // One count per ray and level block (kSplatLevels blocks of `total`), scanned at once: the
  // starts of the level-major order, and the ends of the levels at the block boundaries.
  const int64_t slots = int64_t(kSplatLevels) * total;
  DeviceBuffer<uint64_t> starts(static_cast<size_t>(slots) + 1, stream);
  STRATA_CUDA_CHECK(cudaMemsetAsync(starts.data(), 0, starts.bytes(), stream.get()));
  countSplats<<<blocksFor(total, 256), 256, 0, stream.get()>>>(space, in, frame, starts.data());
  STRATA_CUDA_CHECK(cudaGetLastError());
  exclusiveScanAsync(starts.data(), slots + 1, stream);
  const uint64_t* at[kSplatLevels];
  uint64_t ends[kSplatLevels] = {};
  for (int b = 0; b < kSplatLevels; ++b) at[b] = starts.data() + int64_t(b + 1) * total;
  readBack(at, ends, kSplatLevels, stream);
  SplatLevels levels;
  for (int level = 0; level < kSplatLevels; ++level)
    levels.end[level] = ends[kSplatLevels - 1 - level];
  const uint64_t count = levels.end[0];
  DeviceBuffer<Splat> splats(static_cast<size_t>(count), stream);
  if (count > 0) {
    writeSplats<<<blocksFor(total, 256), 256, 0, stream.get()>>>(space, in, frame, starts.data(),
                                                                 splats.data());
    STRATA_CUDA_CHECK(cudaGetLastError());
  }
  stream.synchronize();
  return std::make_shared<DeviceSplats>(std::move(splats), levels);
}

}  // namespace strata
