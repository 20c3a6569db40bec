// Accounting and stream-ordered allocation of the CUDA backend's device memory.
//
// Every DeviceBuffer allocates through these functions: from the device's default memory pool
// (cudaMallocAsync, released memory is kept for reuse, so the many short-lived scratch buffers
// of an evaluation cost no driver calls), ordered on the calling thread's allocation stream.
#pragma once

#include <cuda_runtime.h>

#include <cstddef>
#include <cstdint>

namespace strata {

// The stream this thread's allocations and frees are ordered on (default: the legacy stream).
void setAllocationStream(cudaStream_t stream);
cudaStream_t allocationStream();

void* deviceAllocate(size_t bytes);  // throws DeviceOutOfMemory / strata::Error
void deviceFree(void* pointer, size_t bytes);

// The most bytes held by DeviceBuffers at once since the last reset.
uint64_t devicePeakBytes();
void resetDevicePeak();

}  // namespace strata
