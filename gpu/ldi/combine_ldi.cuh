// CUDA Booleans of device LDIs, ray by ray: the twin of engine/ldi/combine_ldi.cpp, sharing
// combineRayEvents (engine/ldi/shared_math.h), one thread per ray.
#pragma once

#include <cuda_runtime.h>

#include <memory>
#include <vector>

#include "gpu/ldi/device_ldi.h"

namespace strata {

// Combines the children (all on `grid`, clean lists) with an n-ary operation. Synchronous on
// `stream`. With no children the result is empty.
std::shared_ptr<DeviceLdi> combineOnDevice(RayOp op, const std::vector<const DeviceLdi*>& children,
                                           const Grid& grid, cudaStream_t stream);

// An LDI with no surfels.
std::shared_ptr<DeviceLdi> emptyOnDevice(const Grid& grid, cudaStream_t stream);

}  // namespace strata
