// Process memory as the operating system sees it.
#pragma once

#include <cstdint>

namespace strata {

// Peak resident set size of this process so far, in bytes (0 where unknown).
uint64_t peakResidentBytes();

}  // namespace strata
