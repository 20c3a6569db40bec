#include "engine/util/memory.h"

#include <sys/resource.h>
#include <sys/statvfs.h>

#include <cstdio>
#include <cstring>

namespace strata {

uint64_t peakResidentBytes() {
  struct rusage usage {};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return uint64_t(usage.ru_maxrss) * 1024u;  // Linux reports kilobytes
}

uint64_t availableMemoryBytes() {
  FILE* f = std::fopen("/proc/meminfo", "r");
  if (!f) return 0;
  char line[256];
  uint64_t kib = 0;
  while (std::fgets(line, sizeof(line), f)) {
    unsigned long long v = 0;
    if (std::sscanf(line, "MemAvailable: %llu kB", &v) == 1) {
      kib = v;
      break;
    }
  }
  std::fclose(f);
  return kib * 1024u;
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
