// A CUDA stream with shared ownership: the stream the CUDA backend's work and memory are ordered
// on. Copies share one stream; the last copy to go destroys it (after the work queued on it),
// logging any failure there. Every DeviceBuffer keeps the stream it was allocated on and frees
// on it, so a stream outlives every buffer (and LDI or splats handle) made on it, on whatever
// thread the last of them is released.
#pragma once

#include <cuda_runtime.h>

#include <memory>

namespace strata {

class DeviceStream {
 public:
  // A new non-blocking stream (no implicit ordering with the legacy stream 0) on the calling
  // thread's current device. Throws strata::Error.
  static DeviceStream create();

  DeviceStream() = default;  // no stream: only what an empty DeviceBuffer holds

  // The stream to pass to CUDA calls and launches; null (the legacy stream) when there is none,
  // which DeviceBuffer refuses: never launch on a DeviceStream that was not created.
  cudaStream_t get() const { return owner_ ? owner_->stream : nullptr; }
  explicit operator bool() const { return owner_ != nullptr; }

  // Waits for the work queued on the stream. Throws strata::Error (naming a failed kernel).
  void synchronize() const;

 private:
  struct Owner {
    cudaStream_t stream = nullptr;
    Owner() = default;
    Owner(const Owner&) = delete;
    Owner& operator=(const Owner&) = delete;
    ~Owner();  // synchronizes and destroys the stream; failures are logged, not thrown
  };
  std::shared_ptr<const Owner> owner_;
};

}  // namespace strata
