// libFuzzer target: runPipeline in fuzz_entries.h (what the bytes build and the property
// checked are described there). Build and run: tests/fuzz/README.md.
#include <cstddef>
#include <cstdint>

#include "engine/util/parallel_for.h"
#include "tests/fuzz/fuzz_entries.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  strata::setWorkerCount(1);  // one thread: coverage and timing follow the input alone
  strata::fuzz::runPipeline(data, size);
  return 0;
}
