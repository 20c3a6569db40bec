// Disjoint sets: the concurrent union-find against the serial one, and the dense numbering of
// sets by their roots (engine/util/union_find.h).
#include "engine/util/union_find.h"

#include <gtest/gtest.h>

#include <random>

#include "engine/util/parallel_for.h"

namespace strata {
namespace {

// 200,000 elements (several chunks of the numbering) joined at random into sets: numbered by
// their first member, the same on one thread and on eight, and as the serial union-find says.
TEST(UnionFind, SetsAreNumberedInOrderOfTheirFirstMemberOnAnyThreadCount) {
  constexpr uint32_t kElements = 200000;
  UnionFind serial(kElements);
  ConcurrentUnionFind concurrent(kElements);
  std::mt19937 rng(7);
  for (int k = 0; k < 150000; ++k) {
    const uint32_t a = rng() % kElements, b = rng() % kElements;
    serial.unite(a, b);
    concurrent.unite(a, b);
  }
  std::vector<uint32_t> rootOf(kElements);
  for (uint32_t i = 0; i < kElements; ++i) {
    rootOf[i] = concurrent.find(i);
    ASSERT_EQ(rootOf[i], serial.find(i)) << i;
  }
  // The expected numbers, serially: a new set when its first member comes.
  std::vector<uint32_t> expected(kElements), numberOfRoot(kElements, UINT32_MAX);
  uint32_t next = 0;
  for (uint32_t i = 0; i < kElements; ++i) {
    if (numberOfRoot[rootOf[i]] == UINT32_MAX) numberOfRoot[rootOf[i]] = next++;
    expected[i] = numberOfRoot[rootOf[i]];
  }
  for (const int threads : {1, 8}) {
    setWorkerCount(threads);
    uint32_t sets = 0;
    EXPECT_EQ(numberSetsByRoot(rootOf, &sets), expected) << threads;
    EXPECT_EQ(sets, next) << threads;
  }
  setWorkerCount(0);
  uint32_t none = 1;
  EXPECT_TRUE(numberSetsByRoot({}, &none).empty());
  EXPECT_EQ(none, 0u);
}

}  // namespace
}  // namespace strata
