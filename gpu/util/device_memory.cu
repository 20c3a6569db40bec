#include "gpu/util/device_memory.h"

#include <atomic>
#include <cstdint>
#include <mutex>

#include "gpu/util/cuda_check.h"

namespace strata {
namespace {
thread_local cudaStream_t t_stream = nullptr;
std::atomic<uint64_t> g_inUse{0};
std::atomic<uint64_t> g_peak{0};
std::once_flag g_poolConfigured;

void configurePool() {
  int device = 0;
  if (cudaGetDevice(&device) != cudaSuccess) return;
  cudaMemPool_t pool;
  if (cudaDeviceGetDefaultMemPool(&pool, device) != cudaSuccess) return;
  uint64_t keep = UINT64_MAX;  // keep freed blocks for reuse instead of returning them
  cudaMemPoolSetAttribute(pool, cudaMemPoolAttrReleaseThreshold, &keep);
}
}  // namespace

void setAllocationStream(cudaStream_t stream) {
  t_stream = stream;
}
cudaStream_t allocationStream() {
  return t_stream;
}

void* deviceAllocate(size_t bytes) {
  std::call_once(g_poolConfigured, configurePool);
  void* p = nullptr;
  STRATA_CUDA_CHECK(cudaMallocAsync(&p, bytes, t_stream));
  uint64_t now = g_inUse.fetch_add(bytes) + bytes;
  uint64_t peak = g_peak.load();
  while (now > peak && !g_peak.compare_exchange_weak(peak, now)) {
  }
  return p;
}

void deviceFree(void* pointer, size_t bytes) {
  if (!pointer) return;
  cudaFreeAsync(pointer, t_stream);
  g_inUse.fetch_sub(bytes);
}

uint64_t devicePeakBytes() {
  return g_peak.load();
}
void resetDevicePeak() {
  g_peak.store(g_inUse.load());
}

}  // namespace strata
