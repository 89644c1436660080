// resizeOnHugePages is std::vector::resize(n, value) whatever the allocation it makes, and
// adviseHugePages is harmless on any range. (Whether the kernel backs a range with huge
// pages depends on its settings and free memory; the benchmarks measure that, in
// Documentation/benchmarks-core.md.)
#include "HugePages.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

TEST(HugePages, ResizeKeepsTheContentAndFillsTheRest)
{
  const std::size_t big = 3 * gmm::kHugePageBytes / sizeof(float) + 5; // a new allocation
  std::vector<float> v = { 1.0f, 2.0f, 3.0f };
  gmm::resizeOnHugePages(v, big, 7.0f);
  ASSERT_EQ(v.size(), big);
  EXPECT_EQ(v[0], 1.0f);
  EXPECT_EQ(v[1], 2.0f);
  EXPECT_EQ(v[2], 3.0f);
  EXPECT_EQ(v[3], 7.0f);
  EXPECT_EQ(v[big / 2], 7.0f);
  EXPECT_EQ(v.back(), 7.0f);

  // Within the capacity: no new allocation, the same as resize.
  const float* data = v.data();
  gmm::resizeOnHugePages(v, 10, 9.0f);
  EXPECT_EQ(v.size(), 10u);
  EXPECT_EQ(v.data(), data);
  EXPECT_EQ(v[2], 3.0f);
  gmm::resizeOnHugePages(v, 12, 9.0f);
  EXPECT_EQ(v[10], 9.0f);
  EXPECT_EQ(v[11], 9.0f);

  // Small vectors are resized as they are.
  std::vector<std::uint8_t> small;
  gmm::resizeOnHugePages(small, 100, std::uint8_t(4));
  ASSERT_EQ(small.size(), 100u);
  EXPECT_EQ(small[99], 4);
}

TEST(HugePages, AdviceOnAnyRangeIsHarmless)
{
  gmm::adviseHugePages(nullptr, 1u << 30);
  std::vector<char> a(100, 'x');
  gmm::adviseHugePages(a.data(), a.size()); // smaller than a huge page
  std::vector<char> b(3 * gmm::kHugePageBytes + 123, 'y');
  gmm::adviseHugePages(b.data() + 1, b.size() - 1); // unaligned, already touched
  EXPECT_EQ(a[99], 'x');
  EXPECT_EQ(b[1], 'y');
  EXPECT_EQ(b.back(), 'y');
}
