// Building a CSR axis on the device from per-ray lists written at padded offsets: exclusive
// scan of the counts (CUB), then a compacting copy. Shared by sampling and Booleans.
#pragma once

#include <cuda_runtime.h>

#include "gpu/ldi/device_ldi.h"

namespace strata {

// Exclusive scan of `counts` (rays entries) into `offsets` (rays + 1 entries, the last = the
// total). Returns the total. Throws strata::Error when it exceeds 2^32 - 1. Synchronises
// `stream` to read the total.
uint64_t scanCounts(const uint32_t* counts, int64_t rays, DeviceBuffer<uint32_t>* offsets,
                    cudaStream_t stream, const char* what);

// Copies ray r's counts[r] surfels from scratch + scratchOffset(r) to out.surfels at
// out.offsets[r], after scanCounts filled out.offsets. scratchOffsets[r] is the ray's start in
// the scratch buffer.
void compactRays(const Surfel* scratch, const uint64_t* scratchOffsets, const uint32_t* counts,
                 int64_t rays, DeviceAxisLdi* out, uint64_t total, cudaStream_t stream);

inline unsigned blocksFor(int64_t items, unsigned threads) {
  int64_t blocks = (items + threads - 1) / threads;
  return unsigned(blocks < 1 ? 1 : (blocks > 0x7fffffff ? 0x7fffffff : blocks));
}

}  // namespace strata
