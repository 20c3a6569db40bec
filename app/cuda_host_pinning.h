// The editor's PinHostMemory (ui/mapped_splat_slots.h) over gpu/'s cudaHostRegister
// (gpu/util/host_pinning.h): the mapped GL buffers the preview worker copies device splats into
// become page-locked, so that the copy is one DMA. app/ is where ui/ and gpu/ meet.
#pragma once

#if defined(STRATA_HAS_EDITOR)
#include "ui/mapped_splat_slots.h"

namespace strata {

// The pinning function where this build has the CUDA backend, otherwise an empty one.
ui::PinHostMemory makeCudaHostPinning();

}  // namespace strata
#endif
