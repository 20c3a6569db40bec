// parallelMergeRuns against sorting the concatenated runs: large enough to split into parts,
// runs that interleave, touch and repeat keys across parts' boundaries.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "engine/util/parallel_for.h"
#include "engine/util/parallel_merge.h"

namespace strata {
namespace {

struct Item {
  uint64_t key;
  uint32_t run;  // which run it came from
};

void expectMergeMatchesSort(int threads, bool unique) {
  setWorkerCount(threads);
  std::mt19937_64 rng(42);
  std::vector<std::vector<Item>> runs(7);
  for (size_t r = 0; r < runs.size(); ++r) {
    // Keys from overlapping ranges, many repeated within and across runs.
    std::uniform_int_distribution<uint64_t> key(r * 10000, r * 10000 + 60000 + r * 3);
    const size_t n = r == 3 ? 0 : 20000 + 7000 * r;
    for (size_t i = 0; i < n; ++i) runs[r].push_back({key(rng), uint32_t(r)});
    std::sort(runs[r].begin(), runs[r].end(),
              [](const Item& a, const Item& b) { return a.key < b.key; });
  }
  std::vector<SortedRun<Item>> views;
  std::vector<uint64_t> expected;
  for (const auto& r : runs) {
    views.push_back({r.data(), r.size()});
    for (const Item& i : r) expected.push_back(i.key);
  }
  std::sort(expected.begin(), expected.end());
  if (unique) expected.erase(std::unique(expected.begin(), expected.end()), expected.end());
  const std::vector<Item> merged = parallelMergeRuns(
      views, [](const Item& i) { return i.key; }, unique);
  ASSERT_EQ(merged.size(), expected.size());
  for (size_t i = 0; i < merged.size(); ++i) ASSERT_EQ(merged[i].key, expected[i]) << i;
  setWorkerCount(0);
}

TEST(ParallelMerge, MatchesSortingTheConcatenatedRuns) {
  expectMergeMatchesSort(1, false);
  expectMergeMatchesSort(4, false);
}

TEST(ParallelMerge, KeepsOneElementPerKeyWhenAskedWhereverTheKeyRepeats) {
  expectMergeMatchesSort(1, true);
  expectMergeMatchesSort(4, true);
}

}  // namespace
}  // namespace strata
