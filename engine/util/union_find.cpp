#include "engine/util/union_find.h"

#include "engine/util/parallel_for.h"

namespace strata {

std::vector<uint32_t> numberSetsByRoot(const std::vector<uint32_t>& rootOf, uint32_t* sets) {
  const size_t n = rootOf.size();
  constexpr size_t kChunk = size_t(1) << 16;
  const size_t chunks = (n + kChunk - 1) / kChunk;
  // The roots in each chunk, then the roots before each chunk.
  std::vector<uint32_t> rootsBefore(chunks + 1, 0);
  parallelFor(0, int64_t(chunks), 1, [&](int64_t b, int64_t e) {
    for (int64_t chunk = b; chunk < e; ++chunk)
      for (size_t i = size_t(chunk) * kChunk; i < std::min(n, size_t(chunk + 1) * kChunk); ++i)
        rootsBefore[size_t(chunk) + 1] += rootOf[i] == i;
  });
  for (size_t chunk = 0; chunk < chunks; ++chunk) rootsBefore[chunk + 1] += rootsBefore[chunk];
  if (sets) *sets = rootsBefore[chunks];
  // The roots' numbers first (a root's is read by its members below, once all are written).
  std::vector<uint32_t> number(n);
  parallelFor(0, int64_t(chunks), 1, [&](int64_t b, int64_t e) {
    for (int64_t chunk = b; chunk < e; ++chunk) {
      uint32_t next = rootsBefore[size_t(chunk)];
      for (size_t i = size_t(chunk) * kChunk; i < std::min(n, size_t(chunk + 1) * kChunk); ++i)
        if (rootOf[i] == i) number[i] = next++;
    }
  });
  parallelFor(0, int64_t(n), int64_t(kChunk), [&](int64_t b, int64_t e) {
    for (size_t i = size_t(b); i < size_t(e); ++i)
      if (rootOf[i] != i) number[i] = number[rootOf[i]];
  });
  return number;
}

}  // namespace strata
