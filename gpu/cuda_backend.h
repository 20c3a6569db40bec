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

// The backend on device 0. Throws strata::Error when no device is available.
std::shared_ptr<Backend> makeCudaBackend();

}  // namespace strata
