// Sorting large arrays by a 64-bit key on all workers (parallelFor): a sample sort. Keys are
// sampled, the array is scattered into key ranges by fixed chunks (each chunk's elements keep
// their order), and each range is sorted on its own. Elements with equal keys may end in any
// order among themselves, so use it where equal keys mean equal elements or their order does
// not matter. Takes a second array of the same size while it runs.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "engine/util/parallel_for.h"

namespace strata {

// Sorts `v` by key(element) (a uint64_t), ascending. T: default-constructible and copyable.
template <typename T, typename Allocator, typename Key>
void parallelSortByKey(std::vector<T, Allocator>& v, Key key) {
  const auto less = [&](const T& a, const T& b) { return key(a) < key(b); };
  const size_t n = v.size();
  const int workers = workerCount();
  constexpr size_t kSerialBelow = size_t(1) << 17;
  if (n < kSerialBelow || workers <= 1) {
    std::sort(v.begin(), v.end(), less);
    return;
  }
  // Splitters from an evenly spaced sample: buckets of roughly equal size.
  const size_t buckets = size_t(workers) * 4;
  const size_t samples = buckets * 32;
  std::vector<uint64_t> sample(samples);
  for (size_t i = 0; i < samples; ++i) sample[i] = key(v[i * (n / samples)]);
  std::sort(sample.begin(), sample.end());
  std::vector<uint64_t> split(buckets - 1);
  for (size_t b = 1; b < buckets; ++b) split[b - 1] = sample[b * samples / buckets];
  const auto bucketOf = [&](uint64_t k) {
    return size_t(std::upper_bound(split.begin(), split.end(), k) - split.begin());
  };
  // Counts per (chunk, bucket), then each chunk's place in each bucket.
  constexpr int64_t kChunk = 65536;
  const size_t chunks = (n + kChunk - 1) / kChunk;
  std::vector<uint64_t> at(chunks * buckets, 0);
  parallelFor(0, int64_t(n), kChunk, [&](int64_t b, int64_t e) {
    uint64_t* count = &at[size_t(b / kChunk) * buckets];
    for (int64_t i = b; i < e; ++i) ++count[bucketOf(key(v[size_t(i)]))];
  });
  std::vector<uint64_t> bucketStart(buckets + 1, 0);
  for (size_t b = 0; b < buckets; ++b) {
    uint64_t offset = bucketStart[b];
    for (size_t c = 0; c < chunks; ++c) {
      const uint64_t count = at[c * buckets + b];
      at[c * buckets + b] = offset;
      offset += count;
    }
    bucketStart[b + 1] = offset;
  }
  std::vector<T, Allocator> out(n);
  parallelFor(0, int64_t(n), kChunk, [&](int64_t b, int64_t e) {
    uint64_t* cursor = &at[size_t(b / kChunk) * buckets];
    for (int64_t i = b; i < e; ++i) out[cursor[bucketOf(key(v[size_t(i)]))]++] = v[size_t(i)];
  });
  parallelFor(0, int64_t(buckets), 1, [&](int64_t b, int64_t e) {
    for (int64_t k = b; k < e; ++k)
      std::sort(out.begin() + int64_t(bucketStart[size_t(k)]),
                out.begin() + int64_t(bucketStart[size_t(k) + 1]), less);
  });
  v.swap(out);
}

}  // namespace strata
