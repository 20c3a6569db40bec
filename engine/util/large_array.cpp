#include "engine/util/large_array.h"

#include <sys/mman.h>

#include <cstdint>
#include <cstdlib>

namespace strata {
namespace {

constexpr size_t kHugePage = size_t(2) << 20;

size_t roundedUp(size_t bytes, size_t to) {
  return (bytes + to - 1) / to * to;
}

}  // namespace

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
// Under a sanitizer, from its allocator (still 2 MiB aligned), so that it sees every access.
void* mapLarge(size_t bytes) {
  return bytes == 0 ? nullptr : std::aligned_alloc(kHugePage, roundedUp(bytes, kHugePage));
}

void unmapLarge(void* pointer, size_t) {
  std::free(pointer);
}
#else
void* mapLarge(size_t bytes) {
  if (bytes == 0) return nullptr;
  const size_t size = roundedUp(bytes, kHugePage);
  // Over-map by one huge page and trim both ends, so that the block starts on a 2 MiB boundary
  // (the kernel backs a range with huge pages only where it is so aligned).
  void* raw =
      mmap(nullptr, size + kHugePage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (raw == MAP_FAILED) return nullptr;
  const uintptr_t start = reinterpret_cast<uintptr_t>(raw);
  const uintptr_t aligned = roundedUp(start, kHugePage);
  if (aligned > start) munmap(raw, aligned - start);
  const uintptr_t end = start + size + kHugePage;
  if (end > aligned + size) munmap(reinterpret_cast<void*>(aligned + size), end - aligned - size);
  void* block = reinterpret_cast<void*>(aligned);
#ifdef MADV_HUGEPAGE
  madvise(block, size, MADV_HUGEPAGE);  // a hint: where refused, ordinary pages
#endif
  return block;
}

void unmapLarge(void* pointer, size_t bytes) {
  if (pointer) munmap(pointer, roundedUp(bytes, kHugePage));
}
#endif

}  // namespace strata
