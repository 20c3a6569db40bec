// libFuzzer target: readMeshBytes over OBJ, STL, PLY, OFF and 3MF (see fuzz_entries.h for how
// the first byte picks the format). Build and run: tests/fuzz/README.md.
#include <cstddef>
#include <cstdint>

#include "tests/fuzz/fuzz_entries.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  strata::fuzz::runMeshReaders(data, size);
  return 0;
}
