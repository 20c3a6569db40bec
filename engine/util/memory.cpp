#include "engine/util/memory.h"

#include <sys/resource.h>

namespace strata {

uint64_t peakResidentBytes() {
  struct rusage usage {};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return uint64_t(usage.ru_maxrss) * 1024u;  // Linux reports kilobytes
}

}  // namespace strata
