// CUDA sampling of a placed mesh into a device LDI: the twin of engine/ldi/sample_mesh.cpp,
// with the same per-ray math (engine/ldi/shared_math.h), so both see exactly the same hits.
//
// One pass over the geometry per axis, as the paper's atomic depth peeling: project the
// triangles, count hits per ray with atomics, scan, write the hits at their offsets, then sort
// and normalise each ray's list. Work is spread over (triangle, ray) pairs through a scan of
// each triangle's ray count, so a large triangle does not serialise a warp.
#pragma once

#include <cuda_runtime.h>

#include <memory>

#include "engine/ldi/grid_mesh.h"
#include "gpu/ldi/device_ldi.h"

namespace strata {

// Samples `mesh` (already placed on the grid) with every surfel tagged `leafId`, into an LDI
// on `stream`. Synchronous: returns with `stream` drained. Throws strata::Error
// (DeviceOutOfMemory when the device is full).
std::shared_ptr<DeviceLdi> sampleMeshOnDevice(const GridMesh& mesh, const Grid& grid,
                                              uint32_t leafId, const DeviceStream& stream);

}  // namespace strata
