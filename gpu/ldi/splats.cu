#include "gpu/ldi/csr_build.cuh"
#include "gpu/ldi/splats.cuh"

namespace strata {
namespace {

struct AxisSurfels {
  const uint32_t* offsets[3];
  const Surfel* surfels[3];
};

// counts[R] = splats on global ray R (R over the three axes' concatenated rays).
__global__ void countSplats(RaySpace space, AxisSurfels in, uint64_t* counts) {
  for (int64_t r = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; r < space.total();
       r += int64_t(gridDim.x) * blockDim.x) {
    const int axis = space.axisOf(r);
    const int64_t ray = r - space.base[axis];
    uint64_t n = 0;
    for (uint32_t k = in.offsets[axis][ray]; k < in.offsets[axis][ray + 1]; ++k)
      n += surfelMakesSplat(in.surfels[axis][k], axis) ? 1 : 0;
    counts[r] = n;
  }
}

__global__ void writeSplats(RaySpace space, AxisSurfels in, SplatFrame frame,
                            const uint64_t* starts, Splat* out) {
  for (int64_t r = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; r < space.total();
       r += int64_t(gridDim.x) * blockDim.x) {
    const int axis = space.axisOf(r);
    const int64_t ray = r - space.base[axis];
    uint64_t at = starts[r];
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
  DeviceBuffer<uint64_t> starts(static_cast<size_t>(total) + 1, stream);
  STRATA_CUDA_CHECK(cudaMemsetAsync(starts.data() + total, 0, sizeof(uint64_t), stream.get()));
  countSplats<<<blocksFor(total, 256), 256, 0, stream.get()>>>(space, in, starts.data());
  STRATA_CUDA_CHECK(cudaGetLastError());
  exclusiveScanAsync(starts.data(), total + 1, stream);
  const uint64_t* at[1] = {starts.data() + total};
  uint64_t count = 0;
  readBack(at, &count, 1, stream);
  DeviceBuffer<Splat> splats(static_cast<size_t>(count), stream);
  if (count > 0) {
    writeSplats<<<blocksFor(total, 256), 256, 0, stream.get()>>>(space, in, splatFrame(ldi.grid()),
                                                                 starts.data(), splats.data());
    STRATA_CUDA_CHECK(cudaGetLastError());
  }
  stream.synchronize();
  return std::make_shared<DeviceSplats>(std::move(splats));
}

}  // namespace strata
