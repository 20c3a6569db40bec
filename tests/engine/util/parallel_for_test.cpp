// parallelFor: every index once, the first exception rethrown on the caller, and loops from
// several threads at once (the preview worker and an export job do that). Also run under
// ThreadSanitizer (.ci/test).
#include "engine/util/parallel_for.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#include "engine/util/error.h"
#include "engine/util/union_find.h"

namespace strata {
namespace {

// Sets the worker count for one test and restores the default afterwards.
class WorkerCount {
 public:
  explicit WorkerCount(int threads) { setWorkerCount(threads); }
  ~WorkerCount() { setWorkerCount(0); }
};

TEST(ParallelFor, VisitsEveryIndexOnce) {
  WorkerCount four(4);
  for (int64_t grain : {1, 7, 1000, 5000}) {
    std::vector<std::atomic<int>> visits(4099);
    parallelFor(3, 4099, grain, [&](int64_t begin, int64_t end) {
      EXPECT_LE(end - begin, grain);
      for (int64_t i = begin; i < end; ++i) visits[size_t(i)].fetch_add(1);
    });
    for (size_t i = 0; i < visits.size(); ++i) ASSERT_EQ(visits[i].load(), i < 3 ? 0 : 1) << i;
  }
}

TEST(ParallelFor, RethrowsTheFirstErrorOnTheCaller) {
  WorkerCount four(4);
  EXPECT_THROW(parallelFor(0, 10000, 1,
                           [](int64_t begin, int64_t) {
                             if (begin % 100 == 17) throw Cancelled();
                           }),
               Cancelled);
  EXPECT_THROW(parallelFor(0, 64, 1,
                           [](int64_t begin, int64_t) {
                             if (begin == 63) throw std::runtime_error("last chunk");
                           }),
               std::runtime_error);
}

TEST(ParallelFor, LoopsFromSeveralThreadsAtOnce) {
  WorkerCount three(3);
  std::vector<int64_t> sums(4, 0);
  std::vector<std::thread> callers;
  for (size_t t = 0; t < sums.size(); ++t)
    callers.emplace_back([&, t] {
      std::atomic<int64_t> sum{0};
      parallelFor(0, 20000, 64, [&](int64_t begin, int64_t end) {
        int64_t local = 0;
        for (int64_t i = begin; i < end; ++i) local += i;
        sum.fetch_add(local);
      });
      sums[t] = sum.load();
    });
  for (auto& c : callers) c.join();
  for (int64_t s : sums) EXPECT_EQ(s, int64_t(20000) * 19999 / 2);
}

// Bodies that call parallelFor themselves (an export job's merge inside a tile loop): every
// inner index once, no deadlock, also when an inner loop throws.
TEST(ParallelFor, NestedLoopsFinishAndRethrow) {
  WorkerCount four(4);
  std::vector<std::atomic<int>> visits(64 * 500);
  parallelFor(0, 64, 1, [&](int64_t outer, int64_t) {
    parallelFor(0, 500, 7, [&](int64_t begin, int64_t end) {
      for (int64_t i = begin; i < end; ++i) visits[size_t(outer * 500 + i)].fetch_add(1);
    });
  });
  for (size_t i = 0; i < visits.size(); ++i) ASSERT_EQ(visits[i].load(), 1) << i;
  EXPECT_THROW(parallelFor(0, 16, 1,
                           [](int64_t outer, int64_t) {
                             parallelFor(0, 100, 1, [&](int64_t i, int64_t) {
                               if (outer == 5 && i == 42) throw Cancelled();
                             });
                           }),
               Cancelled);
}

// The threads are kept: thousands of small loops (the per-leaf steps of a scene with many
// parts) run on the same few threads, each loop still spread over several of them.
TEST(ParallelFor, ManySmallLoopsReuseTheSameThreads) {
  WorkerCount four(4);
  static std::atomic<int> threadsSeen{0};  // first visits of a thread (a thread_local per thread)
  threadsSeen = 0;
  int spread = 0;
  for (int loop = 0; loop < 2000; ++loop) {
    std::mutex mutex;
    std::set<std::thread::id> here;
    parallelFor(0, 64, 1, [&](int64_t, int64_t) {
      thread_local bool counted = false;
      if (!counted) {
        counted = true;
        threadsSeen.fetch_add(1);
      }
      if (loop % 100 == 0) std::this_thread::sleep_for(std::chrono::microseconds(200));
      std::lock_guard<std::mutex> lock(mutex);
      here.insert(std::this_thread::get_id());
    });
    spread += here.size() > 1 ? 1 : 0;
  }
  // New threads for every loop would be thousands; kept ones are the pool (grown to the largest
  // worker count asked for so far) and this thread.
  const int most = std::max(8, int(std::thread::hardware_concurrency())) + 1;
  EXPECT_LE(threadsSeen.load(), most);
  EXPECT_GT(spread, 0);  // loops are shared out
}

}  // namespace
}  // namespace strata

namespace strata {
namespace {

TEST(ConcurrentUnionFind, ManyThreadsEndWithTheSetsAndRootsOfOne) {
  constexpr uint32_t n = 200000;
  std::vector<std::pair<uint32_t, uint32_t>> unions;
  uint64_t state = 99;
  for (int i = 0; i < 150000; ++i) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    const uint32_t a = uint32_t(state >> 33) % n;
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    unions.push_back({a, uint32_t(state >> 33) % n});
  }
  UnionFind sequential(n);
  for (auto [a, b] : unions) sequential.unite(a, b);
  ConcurrentUnionFind concurrent(n);
  setWorkerCount(8);
  parallelFor(0, int64_t(unions.size()), 997, [&](int64_t b, int64_t e) {
    for (int64_t i = b; i < e; ++i)
      concurrent.unite(unions[size_t(i)].first, unions[size_t(i)].second);
  });
  setWorkerCount(0);
  for (uint32_t x = 0; x < n; ++x) ASSERT_EQ(concurrent.find(x), sequential.find(x)) << x;
}

}  // namespace
}  // namespace strata
