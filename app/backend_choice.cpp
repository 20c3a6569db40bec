#include "app/backend_choice.h"

#include <algorithm>

#include "engine/eval/cpu_backend.h"
#include "engine/util/error.h"
#if defined(STRATA_HAS_CUDA)
#include "gpu/cuda_backend.h"
#endif

namespace strata {

namespace {
// The choice startChoosingBackend began (main thread only), and the name it was for.
std::future<BackendChoice> g_started;
std::string g_startedName;

BackendChoice choose(const std::string& name, int processOnHost);
}  // namespace

void startChoosingBackend(const std::string& name) {
  if (name != "auto" && name != "cuda") return;
  g_startedName = name;
  g_started = std::async(std::launch::async, [name] { return choose(name, 0); });
}

BackendChoice chooseBackend(const std::string& name, int processOnHost) {
  if (g_started.valid() && name == g_startedName && processOnHost == 0) {
    std::future<BackendChoice> started = std::move(g_started);
    return started.get();
  }
  return choose(name, processOnHost);
}

namespace {
BackendChoice choose(const std::string& name, int processOnHost) {
  if (name != "auto" && name != "cpu" && name != "cuda")
    throw Error("--backend: unknown backend '" + name + "' (expected auto, cpu or cuda)");
  if (name == "cpu") {
    auto cpu = std::make_shared<CpuBackend>();
    return {cpu, "backend " + cpu->description() + " (asked for)"};
  }
#if defined(STRATA_HAS_CUDA)
  std::string why;
  if (cudaDeviceAvailable(&why)) {
    auto cuda = makeCudaBackend(processOnHost % std::max(1, cudaDeviceCount()));
    return {cuda, "backend " + cuda->description() + (name == "auto" ? " (auto)" : " (asked for)"),
            true};
  }
  if (name == "cuda") throw Error("--backend cuda: " + why + "; use --backend cpu");
#else
  (void)processOnHost;  // which GPU: none in this build
  const std::string why = "this build has no CUDA backend (nvcc was not found when it was built)";
  if (name == "cuda") throw Error("--backend cuda: " + why + "; use --backend cpu");
#endif
  auto cpu = std::make_shared<CpuBackend>();
  return {cpu, "backend " + cpu->description() + " (auto: " + why + ")"};
}
}  // namespace

std::vector<std::shared_ptr<Backend>> exportWorkers(const BackendChoice& choice,
                                                    const std::string& gpus, bool given,
                                                    int* perDevice) {
  *perDevice = 1;
  if (!choice.cuda) {
    if (given)
      throw Error("--gpus: exports on several GPUs need the CUDA backend (" + choice.why + ")");
    return {choice.backend};
  }
  int devices = 1;
#if defined(STRATA_HAS_CUDA)
  devices = std::max(1, cudaDeviceCount());
#endif
  int workers = devices;
  if (gpus != "all") {
    size_t used = 0;
    try {
      workers = std::stoi(gpus, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != gpus.size() || workers < 1 || workers > 64)
      throw Error("--gpus: expected all or a number of workers from 1 to 64, got '" + gpus + "'");
  }
  std::vector<std::shared_ptr<Backend>> backends{choice.backend};
#if defined(STRATA_HAS_CUDA)
  for (int w = 1; w < workers; ++w) backends.push_back(makeCudaBackend(w % devices));
#endif
  *perDevice = (workers + devices - 1) / devices;
  return backends;
}

}  // namespace strata
