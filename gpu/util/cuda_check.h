// Checking every CUDA call: failures become strata::Error naming the call's file and line;
// out-of-memory becomes DeviceOutOfMemory so callers can fall back (smaller tiles, the CPU).
// Where nothing may throw (destructors, teardown: frees, stream and event destruction, GL
// unregistration), STRATA_CUDA_LOG writes the failure, with file and line, to stderr instead.
#pragma once

#include <cuda_runtime.h>

#include <string>

#include "engine/util/error.h"

namespace strata {

class DeviceOutOfMemory : public BackendOutOfMemory {
 public:
  explicit DeviceOutOfMemory(const std::string& message) : BackendOutOfMemory(message) {}
};

[[noreturn]] void throwCudaError(cudaError_t status, const char* call, const char* file, int line);
void logCudaError(cudaError_t status, const char* call, const char* file, int line) noexcept;

}  // namespace strata

#define STRATA_CUDA_CHECK(call)                                            \
  do {                                                                     \
    cudaError_t strata_status_ = (call);                                   \
    if (strata_status_ != cudaSuccess)                                     \
      ::strata::throwCudaError(strata_status_, #call, __FILE__, __LINE__); \
  } while (0)

#define STRATA_CUDA_LOG(call)                                            \
  do {                                                                   \
    cudaError_t strata_status_ = (call);                                 \
    if (strata_status_ != cudaSuccess)                                   \
      ::strata::logCudaError(strata_status_, #call, __FILE__, __LINE__); \
  } while (0)
