#include "gpu/util/device_stream.h"

#include "engine/util/error.h"
#include "gpu/util/cuda_check.h"

namespace strata {

DeviceStream DeviceStream::create() {
  auto owner = std::make_shared<Owner>();
  STRATA_CUDA_CHECK(cudaStreamCreateWithFlags(&owner->stream, cudaStreamNonBlocking));
  DeviceStream s;
  s.owner_ = std::move(owner);
  return s;
}

void DeviceStream::synchronize() const {
  if (!owner_) throw Error("internal: synchronizing a DeviceStream that was never created");
  STRATA_CUDA_CHECK(cudaStreamSynchronize(owner_->stream));
}

DeviceStream::Owner::~Owner() {
  if (!stream) return;
  STRATA_CUDA_LOG(cudaStreamSynchronize(stream));
  STRATA_CUDA_LOG(cudaStreamDestroy(stream));
}

}  // namespace strata
