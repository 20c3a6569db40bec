#include "engine/util/thread_priority.h"

#if defined(__linux__)
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cerrno>
#endif

namespace strata {

bool lowerThisThreadPriority(int steps) {
#if defined(__linux__)
  // On Linux the nice value belongs to the thread (task) named by its id.
  const auto tid = static_cast<id_t>(syscall(SYS_gettid));
  errno = 0;
  const int now = getpriority(PRIO_PROCESS, tid);
  if (now == -1 && errno != 0) return false;
  return setpriority(PRIO_PROCESS, tid, now + steps) == 0;
#else
  (void)steps;
  return false;
#endif
}

}  // namespace strata
