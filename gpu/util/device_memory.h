// Accounting and stream-ordered allocation of the CUDA backend's device memory.
//
// Every DeviceBuffer allocates through these functions: from the device's default memory pool
// (cudaMallocAsync; released memory is kept for reuse, so the many short-lived scratch buffers
// of an evaluation cost no driver calls), ordered on the stream the caller names. A block is
// freed on the stream it was allocated on (DeviceBuffer keeps it), after the work queued there.
#pragma once

#include <cuda_runtime.h>

#include <cstddef>
#include <cstdint>

namespace strata {

// Makes the default pool of `device` keep freed blocks for reuse instead of returning them to
// the driver. Throws strata::Error.
void keepFreedDeviceMemory(int device);

// `bytes` of device memory, usable by work queued on `stream` from now on. Throws
// DeviceOutOfMemory / strata::Error.
void* deviceAllocate(size_t bytes, cudaStream_t stream);
// Frees `pointer` (from deviceAllocate, `bytes` long) once the work queued on `stream` so far is
// done. Never throws: a failure is logged to stderr.
void deviceFree(void* pointer, size_t bytes, cudaStream_t stream) noexcept;

// The most bytes held by DeviceBuffers at once (all streams, all threads) since the last reset.
uint64_t devicePeakBytes();
void resetDevicePeak();

}  // namespace strata
