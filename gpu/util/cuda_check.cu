#include "gpu/util/cuda_check.h"

namespace strata {

void throwCudaError(cudaError_t status, const char* call, const char* file, int line) {
  cudaGetLastError();  // clear the sticky error where it is not fatal
  std::string message = std::string("CUDA: ") + cudaGetErrorString(status) + " in " + call + " (" +
                        file + ":" + std::to_string(line) + ")";
  if (status == cudaErrorMemoryAllocation) throw DeviceOutOfMemory(message);
  throw Error(message);
}

}  // namespace strata
