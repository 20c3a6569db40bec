// Arrays of hundreds of megabytes that passes across their layout walk with large strides (an
// offset's per-node lattice: engine/ldi/offset_ldi.h): mapped for the array alone, aligned to
// 2 MiB and marked for transparent huge pages where the system offers them on request
// (madvise mode, as on Debian and Ubuntu): a walk along z then takes one page-table entry per
// 2 MiB instead of one per 4 KiB, and the kernel's first-touch faults are 512 times fewer.
// Elsewhere (huge pages never, or no such call) the same memory in ordinary pages. Under
// AddressSanitizer or ThreadSanitizer, from the sanitizer's allocator, so that it sees every
// access.
//
// Contents are left uninitialised (the kernel gives zeroed pages; callers write before they
// read). Move-only; the memory is unmapped on destruction. Throws std::bad_alloc when the
// mapping fails. T must be trivially copyable.
#pragma once

#include <cstddef>
#include <new>
#include <type_traits>
#include <utility>

namespace strata {

// `bytes` of mapped memory as above (nullptr where the system refuses); release with
// unmapLarge(pointer, bytes).
void* mapLarge(size_t bytes);
void unmapLarge(void* pointer, size_t bytes);

template <typename T>
class LargeArray {
  static_assert(std::is_trivially_copyable<T>::value, "LargeArray holds plain values");

 public:
  LargeArray() = default;
  explicit LargeArray(size_t count) : count_(count) {
    if (count == 0) return;
    data_ = static_cast<T*>(mapLarge(count * sizeof(T)));
    if (!data_) throw std::bad_alloc();
  }
  LargeArray(LargeArray&& o) noexcept
      : data_(std::exchange(o.data_, nullptr)), count_(std::exchange(o.count_, 0)) {}
  LargeArray& operator=(LargeArray&& o) noexcept {
    if (this != &o) {
      reset();
      data_ = std::exchange(o.data_, nullptr);
      count_ = std::exchange(o.count_, 0);
    }
    return *this;
  }
  LargeArray(const LargeArray&) = delete;
  LargeArray& operator=(const LargeArray&) = delete;
  ~LargeArray() { reset(); }

  void reset() {
    if (data_) unmapLarge(data_, count_ * sizeof(T));
    data_ = nullptr;
    count_ = 0;
  }
  T* get() { return data_; }
  const T* get() const { return data_; }
  T& operator[](size_t i) { return data_[i]; }
  const T& operator[](size_t i) const { return data_[i]; }
  size_t size() const { return count_; }

 private:
  T* data_ = nullptr;
  size_t count_ = 0;
};

}  // namespace strata
