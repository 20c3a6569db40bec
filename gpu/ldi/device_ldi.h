// LDIs resident in device memory: the CUDA backend's LdiResource. Same CSR layout as the host
// Ldi (engine/ldi/ldi.h): per axis, rayCount + 1 offsets and the surfels of all rays.
#pragma once

#include <array>

#include "engine/eval/backend.h"
#include "gpu/util/device_buffer.h"

namespace strata {

struct DeviceAxisLdi {
  DeviceBuffer<uint32_t> offsets;
  DeviceBuffer<Surfel> surfels;
};

class DeviceLdi : public LdiResource {
 public:
  explicit DeviceLdi(const Grid& grid) : grid_(grid) {}
  const Grid& grid() const override { return grid_; }
  size_t surfelCount() const override {
    return axes[0].surfels.size() + axes[1].surfels.size() + axes[2].surfels.size();
  }
  size_t bytes() const override {
    size_t b = 0;
    for (const auto& a : axes) b += a.offsets.bytes() + a.surfels.bytes();
    return b;
  }
  std::array<DeviceAxisLdi, 3> axes;

 private:
  Grid grid_;
};

}  // namespace strata
