// CUDA dual contouring of one tile of a device LDI: the twin of engine/contour/contour_tile.cpp,
// running the same per-cell steps (engine/contour/contour_cells.h) one thread per node, cell or
// boundary cell. Only the tile's vertices and triangles come back to the host.
#pragma once

#include <cuda_runtime.h>
#include <glm/vec3.hpp>

#include "engine/contour/contour_tile.h"
#include "gpu/ldi/device_ldi.h"

namespace strata {

// `ldi` is the root's LDI on the tile's window grid (on any stream); see contourTile for the
// rest. Queued on `stream`; synchronous.
TileContour contourTileOnDevice(const DeviceLdi& ldi, const glm::ivec3& globalCells,
                                const glm::ivec3& begin, const glm::ivec3& end,
                                const DeviceStream& stream);

}  // namespace strata
