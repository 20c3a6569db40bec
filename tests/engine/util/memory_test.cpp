// availableMemoryBytes: what a job's estimate is held against. A limit on the process (`ulimit
// -v`) counts, not only the host's free memory: an estimate of 17.9 GiB was accepted against the
// host's 22 GiB under an 8 GB limit and the job then ran out of memory.
#include "engine/util/memory.h"

#include <gtest/gtest.h>

#include <cstring>

#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace strata {
namespace {

TEST(AvailableMemory, AnAddressSpaceLimitCounts) {
  const uint64_t host = availableMemoryBytes();
  ASSERT_GT(host, 0u);
  // In a child (the limit stays there): 1 GiB more than it maps now, where the host has more.
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    struct rlimit limit {};
    getrlimit(RLIMIT_AS, &limit);
    FILE* f = std::fopen("/proc/self/status", "r");
    unsigned long long kib = 0;
    char line[256];
    while (f && std::fgets(line, sizeof(line), f))
      if (std::sscanf(line, "VmSize: %llu kB", &kib) == 1) break;
    if (f) std::fclose(f);
    const rlim_t wanted = rlim_t(kib * 1024ull + (1ull << 30));
    if (limit.rlim_max != RLIM_INFINITY && limit.rlim_max < wanted) _exit(2);  // cannot test
    limit.rlim_cur = wanted;
    if (setrlimit(RLIMIT_AS, &limit) != 0) _exit(2);
    const uint64_t available = availableMemoryBytes();
    _exit(available > 0 && available <= (1ull << 30) + (64ull << 20) ? 0 : 1);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  if (WEXITSTATUS(status) == 2) GTEST_SKIP() << "no address-space limit can be set here";
  EXPECT_EQ(WEXITSTATUS(status), 0) << "the limit was not counted (host: " << host << " bytes)";
}

// residentBytes: what the process holds now, where peakResidentBytes keeps what it once held.
// 256 MiB mapped and touched count in both; unmapped, they leave the resident size (within 64
// MiB of before) and stay in the peak. (Mapped directly: an allocator, or ASan's quarantine, may
// keep freed memory resident.)
TEST(ResidentMemory, MemoryLetGoLeavesTheResidentSizeAndStaysInThePeak) {
  constexpr size_t kBytes = size_t(256) << 20;
  const uint64_t before = residentBytes();
  ASSERT_GT(before, 0u);
  void* block = mmap(nullptr, kBytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  ASSERT_NE(block, MAP_FAILED);
  std::memset(block, 1, kBytes);
  const uint64_t holding = residentBytes();
  EXPECT_GE(holding, before + kBytes - (uint64_t(16) << 20));
  ASSERT_EQ(munmap(block, kBytes), 0);
  const uint64_t after = residentBytes();
  EXPECT_LT(after, before + (uint64_t(64) << 20)) << "the block let go still counts";
  // (The two counters are kept apart by the kernel and may differ by a few pages.)
  EXPECT_GE(peakResidentBytes(), before + kBytes - (uint64_t(16) << 20));
}

}  // namespace
}  // namespace strata
