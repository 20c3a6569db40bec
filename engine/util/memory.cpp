#include "engine/util/memory.h"

#include <sys/resource.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>

namespace strata {

uint64_t peakResidentBytes() {
  struct rusage usage {};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return uint64_t(usage.ru_maxrss) * 1024u;  // Linux reports kilobytes
}

uint64_t residentBytes() {
  // /proc/self/statm: size, resident, ... in pages.
  FILE* f = std::fopen("/proc/self/statm", "r");
  unsigned long long size = 0, resident = 0;
  const bool read = f && std::fscanf(f, "%llu %llu", &size, &resident) == 2;
  if (f) std::fclose(f);
  const long page = sysconf(_SC_PAGESIZE);
  if (!read || page <= 0) return peakResidentBytes();
  return uint64_t(resident) * uint64_t(page);
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

// The room the memory controller leaves this process's control group and each group above it
// (found through /proc/self/cgroup: cgroup v2, or v1's memory controller), the least of them:
// its limit less its use, where the use counts page cache that reclaim would give back
// (inactive_file) as free. False where no group limits memory.
bool cgroupRoom(uint64_t* room) {
  FILE* f = std::fopen("/proc/self/cgroup", "r");
  if (!f) return false;
  char line[4096];
  std::string v2, v1;  // the group's path in each hierarchy ("" where not in one)
  while (std::fgets(line, sizeof(line), f)) {
    std::string text = line;
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
    if (text.rfind("0::", 0) == 0) v2 = text.substr(3);
    const size_t memory = text.find(":memory:");
    if (memory != std::string::npos) v1 = text.substr(memory + 8);
  }
  std::fclose(f);
  struct Hierarchy {
    std::string root, path;
    const char *limit, *usage, *inactive;
  };
  const Hierarchy hierarchies[] = {
      {"/sys/fs/cgroup/memory", v1, "/memory.limit_in_bytes", "/memory.usage_in_bytes",
       "total_inactive_file %llu"},
      {"/sys/fs/cgroup", v2, "/memory.max", "/memory.current", "inactive_file %llu"}};
  bool limited = false;
  for (const Hierarchy& h : hierarchies) {
    if (h.path.empty()) continue;
    std::string path = h.path;
    for (;;) {
      const std::string dir = h.root + (path == "/" ? std::string() : path);
      unsigned long long max = 0, used = 0, inactive = 0;
      if (readValue((dir + h.limit).c_str(), "%llu", &max) &&
          readValue((dir + h.usage).c_str(), "%llu", &used)) {
        readValue((dir + "/memory.stat").c_str(), h.inactive, &inactive);
        const uint64_t held = used > inactive ? used - inactive : 0;
        const uint64_t left = max > held ? max - held : 0;
        *room = limited ? std::min<uint64_t>(*room, left) : left;
        limited = true;
      }
      if (path == "/") break;
      const size_t slash = path.find_last_of('/');
      path = slash == 0 || slash == std::string::npos ? "/" : path.substr(0, slash);
    }
  }
  return limited;
}

}  // namespace

uint64_t availableMemoryBytes() {
  unsigned long long kib = 0;
  if (!readValue("/proc/meminfo", "MemAvailable: %llu kB", &kib)) return 0;
  uint64_t available = uint64_t(kib) * 1024u;
  // What this process may still map where a limit says less: `ulimit -v` (its address space
  // less what it maps now, reserved ranges included: on the safe side) and its control groups'
  // memory (an estimate against the host's memory accepted a job that an 8 GB limit then
  // killed).
  struct rlimit limit {};
  unsigned long long mapped = 0;
  if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY &&
      readValue("/proc/self/status", "VmSize: %llu kB", &mapped)) {
    const uint64_t room = uint64_t(limit.rlim_cur) > mapped * 1024u
                              ? uint64_t(limit.rlim_cur) - uint64_t(mapped) * 1024u
                              : 0;
    available = std::min(available, room);
  }
  uint64_t room = 0;
  if (cgroupRoom(&room)) available = std::min(available, room);
  // 0 means "unknown" to the callers: a limit reached is one byte, which refuses any job.
  return std::max<uint64_t>(available, 1);
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
