// The splats of a device LDI, made on the device (twin of buildSplats in engine/ldi/splats.cpp,
// sharing splatOf and surfelMakesSplat): same splats, same order, bit for bit.
#pragma once

#include <cuda_runtime.h>

#include <memory>

#include "engine/ldi/splats.h"
#include "gpu/ldi/device_ldi.h"
#include "gpu/util/device_buffer.h"

namespace strata {

// Splats resident in device memory: the CUDA backend's SplatResource. Owns its buffer, which
// keeps the stream it lives on (the backend's): it may outlive the backend and be released on
// any thread, its memory then freed on that stream. Complete when splatsOnDevice returns.
class DeviceSplats : public SplatResource {
 public:
  DeviceSplats(DeviceBuffer<Splat> splats, const SplatLevels& levels)
      : splats_(std::move(splats)), levels_(levels) {}
  size_t count() const override { return splats_.size(); }
  SplatLevels levels() const override { return levels_; }
  const Splat* hostData() const override { return nullptr; }
  // Synchronous: queued on stream() (after the work already queued there) and waited for.
  void copyToHost(Splat* out) const override;
  const DeviceBuffer<Splat>& buffer() const { return splats_; }
  // The stream the splats are freed on: a reader on another stream must order its work before
  // that free (gpu/interop makes this stream wait for its copy).
  const DeviceStream& stream() const { return splats_.stream(); }

 private:
  DeviceBuffer<Splat> splats_;
  SplatLevels levels_;
};

// Builds the splats of `ldi` (which may live on any stream) on `stream` and waits for them: the
// result is ready to be read from any stream or thread.
std::shared_ptr<DeviceSplats> splatsOnDevice(const DeviceLdi& ldi, const DeviceStream& stream);

}  // namespace strata
