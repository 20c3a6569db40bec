// WindowHashMap: open addressing with backward-shift erasure, against std::unordered_map.
#include "engine/util/window_hash_map.h"

#include <gtest/gtest.h>

#include <random>
#include <unordered_map>

#include "engine/util/hash.h"

namespace strata::test {
namespace {

struct Mixed {
  uint64_t operator()(uint64_t k) const { return avalanche64(k); }
};
// Every key at one of the eight last slots of the table: long runs that wrap around its end,
// where the backward shift must keep each entry reachable from its home.
struct Clustered {
  uint64_t operator()(uint64_t k) const { return ~(k % 8); }
};

template <typename Hash>
void matchesAReferenceMap(uint64_t keys, int steps) {
  WindowHashMap<uint64_t, uint64_t, Hash> map;
  std::unordered_map<uint64_t, uint64_t> reference;
  std::mt19937_64 random(7);
  for (int step = 0; step < steps; ++step) {
    const uint64_t key = random() % keys;
    if (random() % 3 == 0) {
      map.erase(key);
      reference.erase(key);
    } else {
      bool fresh = false;
      uint64_t* value = map.insert(key, &fresh);
      EXPECT_EQ(fresh, reference.count(key) == 0);
      *value += key + 1;
      reference[key] += key + 1;
    }
    ASSERT_EQ(map.size(), reference.size());
    if (step % 97 == 0)
      for (uint64_t k = 0; k < keys; ++k) {
        const uint64_t* found = map.find(k);
        const auto expected = reference.find(k);
        ASSERT_EQ(found != nullptr, expected != reference.end()) << "key " << k;
        if (found) {
          ASSERT_EQ(*found, expected->second);
        }
      }
  }
}

TEST(WindowHashMap, MatchesAReferenceMapThroughInsertsAndErasures) {
  matchesAReferenceMap<Mixed>(5000, 60000);
}

TEST(WindowHashMap, KeepsEveryEntryReachableInRunsThatWrapAround) {
  matchesAReferenceMap<Clustered>(200, 20000);
}

}  // namespace
}  // namespace strata::test
