#include "app/backend_choice.h"

#include "engine/eval/cpu_backend.h"
#include "engine/util/error.h"

namespace strata {

BackendChoice chooseBackend(const std::string& name) {
  if (name == "cpu") return {std::make_shared<CpuBackend>(), "backend cpu (asked for)"};
  if (name == "auto")
    return {std::make_shared<CpuBackend>(),
            "backend cpu (auto: this build has no CUDA backend yet)"};
  if (name == "cuda")
    throw Error("--backend cuda: this build of strata has no CUDA backend; use --backend cpu");
  throw Error("--backend: unknown backend '" + name + "' (expected auto, cpu or cuda)");
}

}  // namespace strata
