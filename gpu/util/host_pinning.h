// Host memory made page-locked for the CUDA backend's copies into it (cudaHostRegister): a copy
// from the device into such memory is one DMA, where pageable memory takes the driver's staging
// buffers and a second copy by the CPU. Plain C++: callers include it without CUDA (app/ hands
// it to the editor's mapped splat buffers, ui/mapped_splat_slots.h).
//
// Threads: any (the registration is the process's, for every device: cudaHostRegisterPortable).
#pragma once

#include <cstddef>
#include <string>

namespace strata {

// Page-locks `bytes` at `data` (memory that stays mapped until unpinHostMemory). Returns whether
// it did; otherwise *why says CUDA's reason (memory the driver cannot lock: some mappings of
// device memory). Never throws.
bool pinHostMemory(void* data, size_t bytes, std::string* why);
// Undoes pinHostMemory(data, ...). Never throws: a failure is logged to stderr.
void unpinHostMemory(void* data) noexcept;

}  // namespace strata
