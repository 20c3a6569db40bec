// The CUDA backend behind the engine's Backend interface (engine/eval/backend.h). Plain C++:
// callers include this header without CUDA. LDIs stay resident in device memory; download()
// is the one named copy to the host.
#pragma once

#include <memory>
#include <string>

#include "engine/eval/backend.h"

namespace strata {

// True when a CUDA device can be used; otherwise *why says what is missing (no driver, no
// device, ...). Never throws.
bool cudaDeviceAvailable(std::string* why);

// CUDA devices present (0 without a driver). Never throws.
int cudaDeviceCount();

// The backend on `device` (0 .. cudaDeviceCount() - 1). Throws strata::Error when it is not
// available.
std::shared_ptr<Backend> makeCudaBackend(int device = 0);

}  // namespace strata
