// Volume and area of a device LDI, computed on the device (twin of measureLdi in
// engine/ldi/ldi.cpp; sums are reduced in a different order, so results agree to rounding).
#pragma once

#include <cuda_runtime.h>

#include "gpu/ldi/device_ldi.h"

namespace strata {

// Queued on `stream` (the LDI may live on any stream); synchronous.
LdiMeasure measureOnDevice(const DeviceLdi& ldi, const DeviceStream& stream);

}  // namespace strata
