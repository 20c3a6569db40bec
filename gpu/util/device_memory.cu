#include "gpu/util/device_memory.h"

#include <atomic>
#include <cstdint>

#include "gpu/util/cuda_check.h"

namespace strata {
namespace {
std::atomic<uint64_t> g_inUse{0};
std::atomic<uint64_t> g_peak{0};
}  // namespace

void keepFreedDeviceMemory(int device) {
  cudaMemPool_t pool;
  STRATA_CUDA_CHECK(cudaDeviceGetDefaultMemPool(&pool, device));
  uint64_t keep = UINT64_MAX;
  STRATA_CUDA_CHECK(cudaMemPoolSetAttribute(pool, cudaMemPoolAttrReleaseThreshold, &keep));
}

void* deviceAllocate(size_t bytes, cudaStream_t stream) {
  void* p = nullptr;
  STRATA_CUDA_CHECK(cudaMallocAsync(&p, bytes, stream));
  uint64_t now = g_inUse.fetch_add(bytes) + bytes;
  uint64_t peak = g_peak.load();
  while (now > peak && !g_peak.compare_exchange_weak(peak, now)) {
  }
  return p;
}

void deviceFree(void* pointer, size_t bytes, cudaStream_t stream) noexcept {
  if (!pointer) return;
  STRATA_CUDA_LOG(cudaFreeAsync(pointer, stream));
  g_inUse.fetch_sub(bytes);
}

uint64_t devicePeakBytes() {
  return g_peak.load();
}
void resetDevicePeak() {
  g_peak.store(g_inUse.load());
}

}  // namespace strata
