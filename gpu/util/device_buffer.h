// Device memory owned by a host object (RAII), from the stream-ordered pool of
// device_memory.h; contents uninitialised. Use it on the thread's allocation stream.
#pragma once

#include <cuda_runtime.h>

#include <cstddef>
#include <vector>

#include "gpu/util/cuda_check.h"
#include "gpu/util/device_memory.h"

namespace strata {

template <typename T>
class DeviceBuffer {
 public:
  DeviceBuffer() = default;
  explicit DeviceBuffer(size_t count) { resize(count); }
  ~DeviceBuffer() { release(); }
  DeviceBuffer(const DeviceBuffer&) = delete;
  DeviceBuffer& operator=(const DeviceBuffer&) = delete;
  DeviceBuffer(DeviceBuffer&& o) noexcept : data_(o.data_), size_(o.size_) {
    o.data_ = nullptr;
    o.size_ = 0;
  }
  DeviceBuffer& operator=(DeviceBuffer&& o) noexcept {
    if (this != &o) {
      release();
      data_ = o.data_;
      size_ = o.size_;
      o.data_ = nullptr;
      o.size_ = 0;
    }
    return *this;
  }

  // Reallocates (discarding contents) when the size changes.
  void resize(size_t count) {
    if (count == size_) return;
    release();
    if (count > 0) data_ = static_cast<T*>(deviceAllocate(count * sizeof(T)));
    size_ = count;
  }
  void upload(const std::vector<T>& host, cudaStream_t stream) {
    resize(host.size());
    if (size_)
      STRATA_CUDA_CHECK(
          cudaMemcpyAsync(data_, host.data(), size_ * sizeof(T), cudaMemcpyHostToDevice, stream));
  }
  void download(std::vector<T>* host, cudaStream_t stream) const {
    host->resize(size_);
    if (size_)
      STRATA_CUDA_CHECK(
          cudaMemcpyAsync(host->data(), data_, size_ * sizeof(T), cudaMemcpyDeviceToHost, stream));
  }
  T* data() { return data_; }
  const T* data() const { return data_; }
  size_t size() const { return size_; }
  size_t bytes() const { return size_ * sizeof(T); }

 private:
  void release() {
    if (data_) deviceFree(data_, size_ * sizeof(T));
    data_ = nullptr;
    size_ = 0;
  }
  T* data_ = nullptr;
  size_t size_ = 0;
};

}  // namespace strata
