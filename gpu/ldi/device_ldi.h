// LDIs resident in device memory: the CUDA backend's LdiResource. Same CSR layout as the host
// Ldi (engine/ldi/ldi.h): per axis, rayCount + 1 offsets and the surfels of all rays.
//
// Ownership: a DeviceLdi owns its buffers and shares the stream they live on (the backend's),
// so it may outlive the backend and be released on any thread; its memory is then freed on that
// stream. Complete when the backend hands it out (every backend call drains its stream).
#pragma once

#include <array>

#include "engine/eval/backend.h"
#include "gpu/util/device_buffer.h"
#include "gpu/util/device_stream.h"

namespace strata {

// As AxisLdi (engine/ldi/ldi.h): whole (offsets for every ray of the grid) or windowed
// (offsets for the rays of `window` only, made by sampling a solid small against the grid).
struct DeviceAxisLdi {
  bool whole = true;
  RayWindow window;  // meaningful when !whole
  DeviceBuffer<uint32_t> offsets;
  DeviceBuffer<Surfel> surfels;
};

class DeviceLdi : public LdiResource {
 public:
  DeviceLdi(const Grid& grid, const DeviceStream& stream) : stream_(stream), grid_(grid) {}
  const Grid& grid() const override { return grid_; }
  size_t surfelCount() const override {
    return axes[0].surfels.size() + axes[1].surfels.size() + axes[2].surfels.size();
  }
  size_t bytes() const override {
    size_t b = 0;
    for (const auto& a : axes) b += a.offsets.bytes() + a.surfels.bytes();
    return b;
  }
  // The stream its buffers are allocated and freed on (each buffer also keeps it).
  const DeviceStream& stream() const { return stream_; }
  std::array<DeviceAxisLdi, 3> axes;  // buffers on stream()
  bool whole() const { return axes[0].whole && axes[1].whole && axes[2].whole; }

 private:
  DeviceStream stream_;
  Grid grid_;
};

}  // namespace strata
