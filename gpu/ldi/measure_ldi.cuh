// Volume and area of a device LDI, computed on the device (twin of measureLdi in
// engine/ldi/ldi.cpp; sums are reduced in a different order, so results agree to rounding).
#pragma once

#include <cuda_runtime.h>

#include "gpu/ldi/device_ldi.h"

namespace strata {

LdiMeasure measureOnDevice(const DeviceLdi& ldi, cudaStream_t stream);

}  // namespace strata
