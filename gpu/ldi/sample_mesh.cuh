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
#include <vector>

#include "engine/ldi/grid_mesh.h"
#include "gpu/ldi/device_ldi.h"

namespace strata {

// Samples `mesh` (already placed on the grid) with every surfel tagged `leafId`, into an LDI
// on `stream`. Synchronous: returns with `stream` drained. Throws strata::Error
// (DeviceOutOfMemory when the device is full).
std::shared_ptr<DeviceLdi> sampleMeshOnDevice(const GridMesh& mesh, const Grid& grid,
                                              uint32_t leafId, const DeviceStream& stream);

// The same for many meshes at once (meshes[k] tagged leafIds[k]), in one pass: one upload of all
// their triangles, one launch per step over all of them and three waits in all, however many
// meshes there are; each LDI equals what sampleMeshOnDevice makes of its mesh alone. Scratch
// memory grows with the batch (about 40 bytes a ray of every mesh's rays, 80 a triangle, plus
// their raw hits): the caller sizes batches.
std::vector<std::shared_ptr<DeviceLdi>> sampleMeshesOnDevice(
    const std::vector<const GridMesh*>& meshes, const std::vector<uint32_t>& leafIds,
    const Grid& grid, const DeviceStream& stream);

}  // namespace strata
