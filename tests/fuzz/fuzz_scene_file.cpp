// libFuzzer target: parseScene (engine/io/scene_file.h) over arbitrary JSON text. Build and
// run: tests/fuzz/README.md.
#include <cstddef>
#include <cstdint>

#include "tests/fuzz/fuzz_entries.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  strata::fuzz::runSceneFile(data, size);
  return 0;
}
