// Device memory owned by a host object (RAII), from the stream-ordered pool of
// device_memory.h; contents uninitialised.
//
// A buffer knows its stream: it is allocated on the stream it is made with, keeps that stream
// alive (DeviceStream is shared), and is freed on it when released (stream-ordered, after the
// work queued there: a kernel still reading it finishes first). Its transfers are queued on that
// stream too. Work on another stream that reads a buffer must be ordered before the buffer's
// release (finish it, or make the buffer's stream wait for it).
#pragma once

#include <cuda_runtime.h>

#include <cstddef>
#include <vector>

#include "engine/util/error.h"
#include "gpu/util/cuda_check.h"
#include "gpu/util/device_memory.h"
#include "gpu/util/device_stream.h"

namespace strata {

template <typename T>
class DeviceBuffer {
 public:
  DeviceBuffer() = default;  // empty: no memory, no stream
  // `count` elements on `stream` (which must have been created). Throws DeviceOutOfMemory.
  DeviceBuffer(size_t count, const DeviceStream& stream) : stream_(stream) {
    if (!stream_) throw Error("internal: device memory asked for on no stream");
    if (count > 0) data_ = static_cast<T*>(deviceAllocate(count * sizeof(T), stream_.get()));
    size_ = count;
  }
  // A buffer holding a copy of `host`, queued on `stream` (from pageable memory: `host` may
  // change once this returns).
  static DeviceBuffer upload(const std::vector<T>& host, const DeviceStream& stream) {
    DeviceBuffer b(host.size(), stream);
    if (b.size_)
      STRATA_CUDA_CHECK(
          cudaMemcpyAsync(b.data_, host.data(), b.bytes(), cudaMemcpyHostToDevice, stream.get()));
    return b;
  }
  ~DeviceBuffer() { release(); }
  DeviceBuffer(const DeviceBuffer&) = delete;
  DeviceBuffer& operator=(const DeviceBuffer&) = delete;
  DeviceBuffer(DeviceBuffer&& o) noexcept
      : stream_(std::move(o.stream_)), data_(o.data_), size_(o.size_) {
    o.data_ = nullptr;
    o.size_ = 0;
  }
  DeviceBuffer& operator=(DeviceBuffer&& o) noexcept {
    if (this != &o) {
      release();
      stream_ = std::move(o.stream_);
      data_ = o.data_;
      size_ = o.size_;
      o.data_ = nullptr;
      o.size_ = 0;
    }
    return *this;
  }

  // Copies the contents into *host (resized to size()), queued on the buffer's stream: *host is
  // complete once that stream is synchronized.
  template <typename Allocator>
  void downloadAsync(std::vector<T, Allocator>* host) const {
    host->resize(size_);
    if (size_)
      STRATA_CUDA_CHECK(
          cudaMemcpyAsync(host->data(), data_, bytes(), cudaMemcpyDeviceToHost, stream_.get()));
  }
  // Frees the memory now (on its stream) and leaves the buffer empty.
  void reset() noexcept { release(); }

  T* data() { return data_; }
  const T* data() const { return data_; }
  size_t size() const { return size_; }
  size_t bytes() const { return size_ * sizeof(T); }
  // The stream the memory lives on (none for an empty buffer).
  const DeviceStream& stream() const { return stream_; }

 private:
  void release() noexcept {
    if (data_) deviceFree(data_, bytes(), stream_.get());
    data_ = nullptr;
    size_ = 0;
    stream_ = DeviceStream();  // the last buffer of a stream may destroy it here
  }
  DeviceStream stream_;
  T* data_ = nullptr;
  size_t size_ = 0;
};

}  // namespace strata
