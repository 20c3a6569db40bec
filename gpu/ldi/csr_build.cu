#include <cub/device/device_scan.cuh>

#include <string>

#include "gpu/ldi/csr_build.cuh"

namespace strata {
namespace {

__global__ void widenCounts(const uint32_t* counts, int64_t rays, uint64_t* wide) {
  for (int64_t r = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; r <= rays;
       r += int64_t(gridDim.x) * blockDim.x)
    wide[r] = r < rays ? counts[r] : 0;
}

__global__ void narrowOffsets(const uint64_t* wide, int64_t rays, uint32_t* offsets) {
  for (int64_t r = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; r <= rays;
       r += int64_t(gridDim.x) * blockDim.x)
    offsets[r] = uint32_t(wide[r]);
}

__global__ void copyRays(const Surfel* scratch, const uint64_t* scratchOffsets,
                         const uint32_t* counts, int64_t rays, const uint32_t* offsets,
                         Surfel* out) {
  for (int64_t r = blockIdx.x * int64_t(blockDim.x) + threadIdx.x; r < rays;
       r += int64_t(gridDim.x) * blockDim.x) {
    const Surfel* from = scratch + scratchOffsets[r];
    Surfel* to = out + offsets[r];
    for (uint32_t k = 0; k < counts[r]; ++k) to[k] = from[k];
  }
}

}  // namespace

uint64_t scanCounts(const uint32_t* counts, int64_t rays, DeviceBuffer<uint32_t>* offsets,
                    cudaStream_t stream, const char* what) {
  // Scan in 64 bits so that an overflow of the 32-bit offsets is detected, not wrapped.
  DeviceBuffer<uint64_t> wide(size_t(rays) + 1);
  widenCounts<<<blocksFor(rays + 1, 256), 256, 0, stream>>>(counts, rays, wide.data());
  STRATA_CUDA_CHECK(cudaGetLastError());
  size_t tempBytes = 0;
  STRATA_CUDA_CHECK(cub::DeviceScan::ExclusiveSum(nullptr, tempBytes, wide.data(), wide.data(),
                                                  rays + 1, stream));
  DeviceBuffer<unsigned char> temp(tempBytes);
  STRATA_CUDA_CHECK(cub::DeviceScan::ExclusiveSum(temp.data(), tempBytes, wide.data(),
                                                  wide.data(), rays + 1, stream));
  uint64_t total = 0;
  STRATA_CUDA_CHECK(cudaMemcpyAsync(&total, wide.data() + rays, sizeof(uint64_t),
                                    cudaMemcpyDeviceToHost, stream));
  STRATA_CUDA_CHECK(cudaStreamSynchronize(stream));
  checkSurfelCount(total, what);
  offsets->resize(size_t(rays) + 1);
  narrowOffsets<<<blocksFor(rays + 1, 256), 256, 0, stream>>>(wide.data(), rays,
                                                              offsets->data());
  STRATA_CUDA_CHECK(cudaGetLastError());
  return total;
}

void compactRays(const Surfel* scratch, const uint64_t* scratchOffsets, const uint32_t* counts,
                 int64_t rays, DeviceAxisLdi* out, uint64_t total, cudaStream_t stream) {
  out->surfels.resize(size_t(total));
  if (total == 0) return;
  copyRays<<<blocksFor(rays, 256), 256, 0, stream>>>(scratch, scratchOffsets, counts, rays,
                                                     out->offsets.data(), out->surfels.data());
  STRATA_CUDA_CHECK(cudaGetLastError());
}

}  // namespace strata
