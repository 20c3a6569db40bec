#include "app/backend_choice.h"

#include "engine/eval/cpu_backend.h"
#include "engine/util/error.h"
#if defined(STRATA_HAS_CUDA)
#include "gpu/cuda_backend.h"
#endif

namespace strata {

BackendChoice chooseBackend(const std::string& name) {
  if (name != "auto" && name != "cpu" && name != "cuda")
    throw Error("--backend: unknown backend '" + name + "' (expected auto, cpu or cuda)");
  if (name == "cpu") {
    auto cpu = std::make_shared<CpuBackend>();
    return {cpu, "backend " + cpu->description() + " (asked for)"};
  }
#if defined(STRATA_HAS_CUDA)
  std::string why;
  if (cudaDeviceAvailable(&why)) {
    auto cuda = makeCudaBackend();
    return {cuda, "backend " + cuda->description() + (name == "auto" ? " (auto)" : " (asked for)"),
            true};
  }
  if (name == "cuda") throw Error("--backend cuda: " + why + "; use --backend cpu");
#else
  const std::string why = "this build has no CUDA backend (nvcc was not found when it was built)";
  if (name == "cuda") throw Error("--backend cuda: " + why + "; use --backend cpu");
#endif
  auto cpu = std::make_shared<CpuBackend>();
  return {cpu, "backend " + cpu->description() + " (auto: " + why + ")"};
}

}  // namespace strata
