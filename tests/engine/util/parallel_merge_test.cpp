// parallelMergeRuns against sorting the concatenated runs: large enough to split into parts,
// runs that interleave, touch and repeat keys across parts' boundaries.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
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

// Runs of long stretches (a tile's rows) that interleave, with keys repeated across runs: the
// merge takes equal keys in run order (with `unique`, the first run's), as a stable sort of the
// runs' concatenation does.
TEST(ParallelMerge, TakesEqualKeysInRunOrderAcrossLongStretches) {
  for (const int threads : {1, 4})
    for (const bool unique : {false, true}) {
      setWorkerCount(threads);
      std::vector<std::vector<Item>> runs(5);
      for (uint32_t r = 0; r < runs.size(); ++r)
        for (uint64_t row = 0; row < 400; ++row)
          for (uint64_t k = 0; k < 300; ++k)  // rows of 300, runs overlapping by 40 keys a row
            runs[r].push_back({row * 2000 + r * 260 + k, r});
      std::vector<SortedRun<Item>> views;
      std::vector<Item> expected;
      for (const auto& r : runs) {
        views.push_back({r.data(), r.size()});
        expected.insert(expected.end(), r.begin(), r.end());
      }
      std::stable_sort(expected.begin(), expected.end(),
                       [](const Item& a, const Item& b) { return a.key < b.key; });
      if (unique)
        expected.erase(std::unique(expected.begin(), expected.end(),
                                   [](const Item& a, const Item& b) { return a.key == b.key; }),
                       expected.end());
      const std::vector<Item> merged = parallelMergeRuns(
          views, [](const Item& i) { return i.key; }, unique);
      ASSERT_EQ(merged.size(), expected.size());
      for (size_t i = 0; i < merged.size(); ++i) {
        ASSERT_EQ(merged[i].key, expected[i].key) << i;
        ASSERT_EQ(merged[i].run, expected[i].run) << i << (unique ? " unique" : "");
      }
    }
  setWorkerCount(0);
}

// RunMerge::each visits every element of the merge once, at its place, from several threads;
// one run (the single-tile export) is visited in place, in its own order.
TEST(ParallelMerge, EachVisitsEveryPlaceOnceAndOneRunInPlace) {
  setWorkerCount(4);
  std::vector<std::vector<Item>> runs(3);
  for (uint32_t r = 0; r < 3; ++r)
    for (uint64_t k = 0; k < 70000; ++k) runs[r].push_back({3 * k + r, r});
  std::vector<SortedRun<Item>> views;
  for (const auto& r : runs) views.push_back({r.data(), r.size()});
  const auto key = [](const Item& i) { return i.key; };
  const RunMerge<Item, decltype(key)> merge(views, key, false);
  ASSERT_EQ(merge.size(), 210000u);
  std::vector<std::atomic<int>> seen(merge.size());
  std::vector<uint64_t> at(merge.size(), 0);
  merge.each([&](size_t i, const Item& e) {
    ++seen[i];
    at[i] = e.key;
  });
  for (size_t i = 0; i < at.size(); ++i) {
    ASSERT_EQ(seen[i].load(), 1) << i;
    ASSERT_EQ(at[i], uint64_t(i)) << i;  // keys 0, 1, 2, ... interleaved from the three runs
  }
  // eachWith: each stretch its own context, met in order from its first element on.
  struct Stretch {
    bool started = false;
    uint64_t lastKey = 0;
  };
  std::atomic<int> outOfOrder{0};
  std::vector<std::atomic<int>> seenWith(merge.size());
  merge.eachWith<Stretch>([&](Stretch& s, size_t i, const Item& e) {
    if (s.started && e.key <= s.lastKey) ++outOfOrder;
    s.started = true;
    s.lastKey = e.key;
    ++seenWith[i];
  });
  EXPECT_EQ(outOfOrder.load(), 0);
  for (size_t i = 0; i < seenWith.size(); ++i) ASSERT_EQ(seenWith[i].load(), 1) << i;
  const std::vector<SortedRun<Item>> one = {views[1]};
  const RunMerge<Item, decltype(key)> alone(one, key, false);
  std::vector<uint64_t> order(alone.size(), 0);
  alone.each([&](size_t i, const Item& e) { order[i] = e.key; });
  for (size_t i = 0; i < order.size(); ++i) ASSERT_EQ(order[i], runs[1][i].key) << i;
  setWorkerCount(0);
}

}  // namespace
}  // namespace strata
