#include "gpu/util/host_pinning.h"

#include <cuda_runtime.h>

#include <cstdio>

namespace strata {

bool pinHostMemory(void* data, size_t bytes, std::string* why) {
  const cudaError_t status = cudaHostRegister(data, bytes, cudaHostRegisterPortable);
  if (status == cudaSuccess) return true;
  cudaGetLastError();  // not sticky: clear it for the next call
  if (why) *why = cudaGetErrorString(status);
  return false;
}

void unpinHostMemory(void* data) noexcept {
  const cudaError_t status = cudaHostUnregister(data);
  if (status == cudaSuccess) return;
  cudaGetLastError();
  std::fprintf(stderr, "strata: cudaHostUnregister failed: %s\n", cudaGetErrorString(status));
}

}  // namespace strata
