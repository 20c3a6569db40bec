// The splats of a device LDI, made on the device (twin of buildSplats in engine/ldi/splats.cpp,
// sharing splatOf and surfelMakesSplat): same splats, same order, bit for bit.
#pragma once

#include <cuda_runtime.h>

#include <memory>

#include "engine/ldi/splats.h"
#include "gpu/ldi/device_ldi.h"
#include "gpu/util/device_buffer.h"

namespace strata {

// Splats resident in device memory: the CUDA backend's SplatResource.
class DeviceSplats : public SplatResource {
 public:
  size_t count() const override { return splats.size(); }
  const Splat* hostData() const override { return nullptr; }
  void copyToHost(Splat* out) const override;
  DeviceBuffer<Splat> splats;
};

// Builds the splats of `ldi` on `stream` and waits for them (the result is ready to be read
// from any stream or thread).
std::shared_ptr<DeviceSplats> splatsOnDevice(const DeviceLdi& ldi, cudaStream_t stream);

}  // namespace strata
