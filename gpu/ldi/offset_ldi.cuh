// CUDA offsets of device LDIs: the twin of engine/ldi/offset_ldi.cpp (same method, same
// steps, same order of passes), sharing its per-line math (engine/ldi/offset_math.h), so the
// result is bit for bit the CPU's. One thread per line of nodes for the distance transform, one
// per ray for the result's surfels.
//
// Memory: 37 bytes per node of the grid window while it runs (two distance/leaf pairs for the
// passes, the running minimum and its leaf, the inside flags, and the envelope's scratch), on
// top of the LDIs: 3.7 GB for a grid of 100 M nodes (512 x 420 x 470 cells).
#pragma once

#include <cuda_runtime.h>

#include <memory>

#include "gpu/ldi/device_ldi.h"

namespace strata {

// The offset by `distance` (scene units) of `whole`'s solid (every axis whole; complete; on any
// stream), on its grid, allocated and computed on `stream`. Synchronous: returns with `stream`
// drained. Throws strata::Error for a non-finite distance, DeviceOutOfMemory when the grid's
// scratch does not fit.
std::shared_ptr<DeviceLdi> offsetOnDevice(const DeviceLdi& whole, double distance,
                                          const DeviceStream& stream);

}  // namespace strata
