// HostArray<T>: a std::vector whose resize leaves new elements of a trivial type uninitialised
// (default-initialised) instead of zeroing them. For arrays of hundreds of megabytes that are
// sized once and then written by parallel workers (a tile's contour vertices and triangles): the
// zeroing pass ran on one thread and took the first touch of every page, which the workers'
// own writes then do in parallel. Callers write every element before reading it.
#pragma once

#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace strata {

template <typename T, typename Base = std::allocator<T>>
class DefaultInitAllocator : public Base {
  using Traits = std::allocator_traits<Base>;

 public:
  template <typename U>
  struct rebind {
    using other = DefaultInitAllocator<U, typename Traits::template rebind_alloc<U>>;
  };
  using Base::Base;
  DefaultInitAllocator() = default;
  template <typename U, typename B>
  DefaultInitAllocator(const DefaultInitAllocator<U, B>& other) noexcept : Base(other) {}

  // Without arguments: default-initialised (for a trivial type, left as the memory was).
  template <typename U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible<U>::value) {
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    Traits::construct(static_cast<Base&>(*this), p, std::forward<Args>(args)...);
  }
};

template <typename T>
using HostArray = std::vector<T, DefaultInitAllocator<T>>;

}  // namespace strata
