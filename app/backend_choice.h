// The one place that picks a backend: --backend auto|cpu|cuda.
#pragma once

#include <future>
#include <memory>
#include <string>
#include <vector>

#include "engine/eval/backend.h"

namespace strata {

struct BackendChoice {
  std::shared_ptr<Backend> backend;
  std::string why;    // one line for the user: what was chosen and why
  bool cuda = false;  // the CUDA backend (its splats can go to GL through CUDA-GL interop)
};

// auto: CUDA when this build has it and a device is present, otherwise the CPU.
// cpu:  the CPU backend. cuda: the CUDA backend, or strata::Error saying why it is unavailable.
// `processOnHost`: this process's number among those of one job on its host (distributed
// exports), which picks its GPU: device processOnHost % devices.
// A choice started by startChoosingBackend(name) for process 0 is taken from there.
BackendChoice chooseBackend(const std::string& name, int processOnHost = 0);

// Starts chooseBackend(name, 0) on a thread of its own, so that the CUDA driver's start (about
// 0.3 s a process) overlaps what the command does before it needs the backend (reading its
// meshes); the next chooseBackend(name, 0) waits for it and takes it. Nothing for "cpu" (made
// in no time) or any other name. Call from the main thread, before chooseBackend.
void startChoosingBackend(const std::string& name);

// The backends of an export for `--gpus N|all` (`given`: the option was on the command line;
// its default is all): the chosen backend first, then CUDA backends on the next devices, worker
// i on device i % devices, so N above the device count puts several workers on one device
// (one's host-side contouring overlaps another's device work). One worker for the CPU backend.
// *perDevice: the most workers on one device. Throws strata::Error for a bad value, or --gpus
// given without the CUDA backend.
std::vector<std::shared_ptr<Backend>> exportWorkers(const BackendChoice& choice,
                                                    const std::string& gpus, bool given,
                                                    int* perDevice);

}  // namespace strata
