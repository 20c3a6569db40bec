#include "engine/util/memory.h"

#include <sys/resource.h>
#include <sys/statvfs.h>

#include <algorithm>
#include <cstdio>
#include <cstring>

namespace strata {

uint64_t peakResidentBytes() {
  struct rusage usage {};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return uint64_t(usage.ru_maxrss) * 1024u;  // Linux reports kilobytes
}

namespace {

// The first value `format` (one %llu) reads from a line of the file at `path`; false when none.
bool readValue(const char* path, const char* format, unsigned long long* value) {
  FILE* f = std::fopen(path, "r");
  if (!f) return false;
  char line[256];
  bool found = false;
  while (!found && std::fgets(line, sizeof(line), f)) found = std::sscanf(line, format, value) == 1;
  std::fclose(f);
  return found;
}

}  // namespace

uint64_t availableMemoryBytes() {
  unsigned long long kib = 0;
  if (!readValue("/proc/meminfo", "MemAvailable: %llu kB", &kib)) return 0;
  uint64_t available = uint64_t(kib) * 1024u;
  // What this process may still map where a limit says less: `ulimit -v` (its address space
  // less what it maps now) and its control group's memory (cgroup v2, else v1) less its use (an
  // estimate against the host's memory accepted a job that a 8 GB limit then killed).
  struct rlimit limit {};
  unsigned long long mapped = 0, max = 0, used = 0;
  if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY &&
      readValue("/proc/self/status", "VmSize: %llu kB", &mapped)) {
    const uint64_t room = uint64_t(limit.rlim_cur) > mapped * 1024u
                              ? uint64_t(limit.rlim_cur) - uint64_t(mapped) * 1024u
                              : 0;
    available = std::min(available, room);
  }
  if ((readValue("/sys/fs/cgroup/memory.max", "%llu", &max) &&
       readValue("/sys/fs/cgroup/memory.current", "%llu", &used)) ||
      (readValue("/sys/fs/cgroup/memory/memory.limit_in_bytes", "%llu", &max) &&
       readValue("/sys/fs/cgroup/memory/memory.usage_in_bytes", "%llu", &used)))
    available = std::min<uint64_t>(available, max > used ? max - used : 0);
  return available;
}

uint64_t freeDiskBytesForFile(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  if (slash == std::string::npos) return freeDiskBytes(".");
  return freeDiskBytes(slash == 0 ? "/" : path.substr(0, slash));
}

uint64_t freeDiskBytes(const std::string& folder) {
  struct statvfs fs {};
  if (statvfs(folder.empty() ? "." : folder.c_str(), &fs) != 0) return 0;
  return uint64_t(fs.f_bavail) * uint64_t(fs.f_frsize);
}

}  // namespace strata
