#include "engine/util/large_array.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <numeric>

namespace strata {
namespace {

TEST(LargeArray, HoldsWhatIsWrittenOnBlocksAlignedForHugePages) {
  LargeArray<uint32_t> a((size_t(5) << 20) + 3);  // 20 MiB and a bit: spans several huge pages
  ASSERT_NE(a.get(), nullptr);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(a.get()) % (uintptr_t(2) << 20), 0u);
  std::iota(a.get(), a.get() + a.size(), uint32_t(7));
  EXPECT_EQ(a[0], 7u);
  EXPECT_EQ(a[a.size() - 1], uint32_t(a.size() - 1 + 7));
}

TEST(LargeArray, MovesOwnershipAndReleasesOnce) {
  LargeArray<float> a(1000);
  a[999] = 2.5f;
  float* data = a.get();
  LargeArray<float> b(std::move(a));
  EXPECT_EQ(a.get(), nullptr);
  EXPECT_EQ(a.size(), 0u);
  EXPECT_EQ(b.get(), data);
  EXPECT_EQ(b[999], 2.5f);
  LargeArray<float> c;
  c = std::move(b);
  EXPECT_EQ(c.get(), data);
  c.reset();
  EXPECT_EQ(c.get(), nullptr);
  EXPECT_EQ(LargeArray<uint8_t>(0).get(), nullptr);  // nothing mapped for nothing
}

}  // namespace
}  // namespace strata
