#include "app/cuda_host_pinning.h"

#if defined(STRATA_HAS_EDITOR)

#if defined(STRATA_HAS_CUDA)
#include "gpu/util/host_pinning.h"
#endif

namespace strata {

ui::PinHostMemory makeCudaHostPinning() {
#if defined(STRATA_HAS_CUDA)
  return [](void* data, size_t bytes, std::string* why) -> std::function<void()> {
    if (!pinHostMemory(data, bytes, why)) return {};
    return [data] { unpinHostMemory(data); };
  };
#else
  return {};
#endif
}

}  // namespace strata

#endif
