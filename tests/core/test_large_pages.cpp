// The allocator behind horizon planes and the sweep's buffers: blocks of 2 MB or more start on a
// 2 MB boundary (a huge page can only back a whole aligned 2 MB), smaller ones are ordinary, and
// every block holds what is written to it.
#include <gtest/gtest.h>

#include <cstdint>
#include <numeric>
#include <vector>

#include "skyview/core/large_pages.h"

using namespace skyview;

TEST(LargePages, LargeBlocksStartOnAHugePageAndHoldTheirValues) {
  const std::size_t n = 5 * kHugePageBytes / sizeof(float) + 3;  // not a whole number of huge pages
  LargeBuffer<float> b = allocate_large<float>(n);
  ASSERT_NE(b.get(), nullptr);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(b.get()) % kHugePageBytes, 0u);
  for (std::size_t i = 0; i < n; ++i) b[i] = static_cast<float>(i % 1000);
  EXPECT_EQ(b[n - 1], static_cast<float>((n - 1) % 1000));
  EXPECT_EQ(b[kHugePageBytes / sizeof(float)], static_cast<float>((kHugePageBytes / sizeof(float)) % 1000));
}

TEST(LargePages, SmallAndEmptyBlocksAreUsable) {
  LargeBuffer<double> none = allocate_large<double>(0);
  EXPECT_NE(none.get(), nullptr);
  LargeBuffer<double> few = allocate_large<double>(3);
  few[0] = 1.5, few[2] = -2.5;
  EXPECT_EQ(few[0] + few[2], -1.0);
}

TEST(LargePages, AVectorOnThemGrowsAndCopiesLikeAnyOther) {
  std::vector<float, LargePageAllocator<float>> v(1 << 20);  // 4 MB
  std::iota(v.begin(), v.end(), 0.0f);
  v.resize(3 << 20);
  EXPECT_EQ(v[(1 << 20) - 1], static_cast<float>((1 << 20) - 1));
  EXPECT_EQ(v[(3 << 20) - 1], 0.0f);  // value-initialised when grown
  const auto copy = v;
  EXPECT_EQ(copy, v);
}
