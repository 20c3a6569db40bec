#include "engine/util/thread_priority.h"

#if defined(__linux__)
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cerrno>
#endif

namespace strata {

namespace {
#if defined(__linux__)
id_t thisThreadId() {
  return static_cast<id_t>(syscall(SYS_gettid));  // the nice value belongs to the task
}
#endif
}  // namespace

int thisThreadNiceValue() {
#if defined(__linux__)
  errno = 0;
  const int nice = getpriority(PRIO_PROCESS, thisThreadId());
  return nice == -1 && errno != 0 ? 0 : nice;
#else
  return 0;
#endif
}

bool lowerThisThreadPriority(int steps) {
#if defined(__linux__)
  errno = 0;
  const int now = getpriority(PRIO_PROCESS, thisThreadId());
  if (now == -1 && errno != 0) return false;
  return setpriority(PRIO_PROCESS, thisThreadId(), now + steps) == 0;
#else
  (void)steps;
  return false;
#endif
}

}  // namespace strata
