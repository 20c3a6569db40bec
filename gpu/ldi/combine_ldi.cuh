// CUDA Booleans of device LDIs, ray by ray: the twin of engine/ldi/combine_ldi.cpp, sharing
// gatherRayEvents and combineRayEvents (engine/ldi/shared_math.h), one thread per ray.
#pragma once

#include <cuda_runtime.h>

#include <memory>
#include <vector>

#include "gpu/ldi/device_ldi.h"

namespace strata {

// Combines the children (all on `grid`, clean lists, complete) with an n-ary operation, into an
// LDI allocated on `stream`; the children may live on any stream. Synchronous: returns with
// `stream` drained. With no children the result is empty.
std::shared_ptr<DeviceLdi> combineOnDevice(RayOp op, const std::vector<const DeviceLdi*>& children,
                                           const Grid& grid, const DeviceStream& stream);

// An LDI with no surfels, on `stream` (synchronous).
std::shared_ptr<DeviceLdi> emptyOnDevice(const Grid& grid, const DeviceStream& stream);

}  // namespace strata
