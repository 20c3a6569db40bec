// The editor's DeviceSplatCopier (ui/device_splat_copier.h) over gpu/'s CUDA-GL interop
// (gpu/interop/gl_splat_buffer.h). app/ is where ui/ and gpu/ meet.
#pragma once

#include <memory>

#if defined(STRATA_HAS_EDITOR)
#include "ui/device_splat_copier.h"

namespace strata {

// A copier when this build has CUDA-GL interop, otherwise null.
std::unique_ptr<ui::DeviceSplatCopier> makeCudaGlSplatCopier();

}  // namespace strata
#endif
