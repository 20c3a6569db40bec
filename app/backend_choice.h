// The one place that picks a backend: --backend auto|cpu|cuda.
#pragma once

#include <memory>
#include <string>

#include "engine/eval/backend.h"

namespace strata {

struct BackendChoice {
  std::shared_ptr<Backend> backend;
  std::string why;    // one line for the user: what was chosen and why
  bool cuda = false;  // the CUDA backend (its splats can go to GL through CUDA-GL interop)
};

// auto: CUDA when this build has it and a device is present, otherwise the CPU.
// cpu:  the CPU backend. cuda: the CUDA backend, or strata::Error saying why it is unavailable.
BackendChoice chooseBackend(const std::string& name);

}  // namespace strata
