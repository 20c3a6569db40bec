#include <cstdio>

#include "gpu/util/cuda_check.h"

namespace strata {

void throwCudaError(cudaError_t status, const char* call, const char* file, int line) {
  cudaGetLastError();  // clear the sticky error where it is not fatal
  std::string message = std::string("CUDA: ") + cudaGetErrorString(status) + " in " + call + " (" +
                        file + ":" + std::to_string(line) + ")";
  if (status == cudaErrorMemoryAllocation) throw DeviceOutOfMemory(message);
  throw Error(message);
}

void logCudaError(cudaError_t status, const char* call, const char* file, int line) noexcept {
  cudaGetLastError();  // as above: later calls must not report it again
  std::fprintf(stderr, "strata: CUDA: %s in %s (%s:%d)\n", cudaGetErrorString(status), call, file,
               line);
}

}  // namespace strata
