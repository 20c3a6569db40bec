// parallelSortByKey: the same keys in the same order as std::sort, on arrays large enough to be
// split into buckets, with many equal keys, already sorted runs (tiles), and one key only.
#include "engine/util/parallel_sort.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace strata {
namespace {

struct Item {
  uint64_t key = 0;
  uint32_t payload = 0;  // equal keys carry equal payloads here
};

std::vector<uint64_t> keysOf(const std::vector<Item>& items) {
  std::vector<uint64_t> keys;
  for (const Item& i : items) keys.push_back(i.key);
  return keys;
}

void expectSorted(std::vector<Item> items, int workers) {
  setWorkerCount(workers);
  std::vector<uint64_t> expected = keysOf(items);
  std::sort(expected.begin(), expected.end());
  parallelSortByKey(items, [](const Item& i) { return i.key; });
  setWorkerCount(0);
  EXPECT_EQ(keysOf(items), expected);
  for (const Item& i : items) ASSERT_EQ(i.payload, uint32_t(i.key * 2654435761u)) << i.key;
}

Item item(uint64_t key) {
  return Item{key, uint32_t(key * 2654435761u)};
}

TEST(ParallelSort, SortsLikeStdSort) {
  uint64_t state = 12345;
  auto next = [&] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return state >> 11;
  };
  std::vector<Item> random, duplicates, runs, same;
  for (int i = 0; i < 700000; ++i) random.push_back(item(next()));
  for (int i = 0; i < 500000; ++i) duplicates.push_back(item(next() % 1000));
  for (int tile = 0; tile < 8; ++tile)  // eight sorted runs of interleaved keys, as tiles give
    for (uint64_t k = 0; k < 60000; ++k) runs.push_back(item(k * 8 + uint64_t(tile)));
  for (int i = 0; i < 300000; ++i) same.push_back(item(42));
  for (int workers : {1, 3, 8}) {
    expectSorted(random, workers);
    expectSorted(duplicates, workers);
    expectSorted(runs, workers);
    expectSorted(same, workers);
  }
  expectSorted({}, 4);
  expectSorted({item(3), item(1), item(2)}, 4);
}

}  // namespace
}  // namespace strata
