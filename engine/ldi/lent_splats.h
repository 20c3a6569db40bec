// Host memory for splats, lent by whoever shows them. The preview worker copies a backend's
// device splats to the host when the viewer cannot take them on the device (no CUDA-GL
// interop); where the viewer lends memory its GL reads (the editor: persistently mapped GL
// buffers, ui/mapped_splat_slots.h), the UI thread copies nothing more: no upload into GL.
#pragma once

#include <cstddef>
#include <cstring>
#include <functional>
#include <memory>

#include "engine/ldi/splats.h"

namespace strata {

// Splats in a region of host memory that a HostSplatLender lent. The region is the holder's
// alone until this is destroyed (any thread), which gives it back.
class LentHostSplats : public SplatResource {
 public:
  // `data`: room for `count` splats; `giveBack` runs once, when this is destroyed.
  LentHostSplats(Splat* data, size_t count, const SplatLevels& levels,
                 std::function<void()> giveBack)
      : data_(data), count_(count), levels_(levels), giveBack_(std::move(giveBack)) {}
  ~LentHostSplats() override {
    if (giveBack_) giveBack_();
  }
  LentHostSplats(const LentHostSplats&) = delete;
  LentHostSplats& operator=(const LentHostSplats&) = delete;
  size_t count() const override { return count_; }
  SplatLevels levels() const override { return levels_; }
  const Splat* hostData() const override { return data_; }
  // The region, for the one who fills it before handing this on (the worker).
  Splat* writableData() { return data_; }
  void copyToHost(Splat* out) const override {
    if (count_ > 0) std::memcpy(out, data_, count_ * sizeof(Splat));
  }

 private:
  Splat* data_;
  size_t count_;
  SplatLevels levels_;
  std::function<void()> giveBack_;
};

// What lends the regions. Threads: lend() on the worker's thread; the implementation says how
// its regions come and go on its own thread.
class HostSplatLender {
 public:
  virtual ~HostSplatLender() = default;
  // A region for `count` splats with `levels`, or null when none is free or large enough (the
  // worker then copies into an array of its own; the lender may make room for the next time).
  virtual std::shared_ptr<LentHostSplats> lend(size_t count, const SplatLevels& levels) = 0;
};

}  // namespace strata
