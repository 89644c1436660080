// gmm::HeightBuffer (Filters/HeightBuffer.h): the reader's heights, which the output's
// vtkFloatArray adopts and frees with std::free.
#include "HeightBuffer.h"
#include "HugePages.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <utility>

namespace
{

TEST(HeightBuffer, AssignCopyMoveAndRelease)
{
  gmm::HeightBuffer a(5, 2.5f);
  ASSERT_EQ(a.size(), 5u);
  for (float v : a)
  {
    EXPECT_EQ(v, 2.5f);
  }
  a[3] = 7.0f;
  gmm::HeightBuffer b = a; // deep
  b[3] = 1.0f;
  EXPECT_EQ(a[3], 7.0f);
  EXPECT_NE(a.data(), b.data());
  gmm::HeightBuffer c = std::move(a);
  EXPECT_TRUE(a.empty());
  EXPECT_EQ(a.data(), nullptr);
  ASSERT_EQ(c.size(), 5u);
  EXPECT_EQ(c[3], 7.0f);
  c.swap(b);
  EXPECT_EQ(c[3], 1.0f);
  EXPECT_EQ(b[3], 7.0f);
  // Released memory belongs to the caller (as vtkFloatArray::SetArray with
  // VTK_DATA_ARRAY_FREE takes it); the buffer is empty after.
  float* p = b.release();
  EXPECT_TRUE(b.empty());
  EXPECT_EQ(p[3], 7.0f);
  std::free(p);
  c.clear();
  EXPECT_TRUE(c.empty());
  c.assign(0);
  EXPECT_TRUE(c.empty());
}

TEST(HeightBuffer, DemSizedBuffersStartOnAHugePage)
{
  const std::size_t n = 3 * gmm::kHugePageBytes / sizeof(float) + 7; // not a whole page
  gmm::HeightBuffer big(n, -1.0f);
  ASSERT_EQ(big.size(), n);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(big.data()) % gmm::kHugePageBytes, 0u);
  EXPECT_EQ(big[0], -1.0f);
  EXPECT_EQ(big[n - 1], -1.0f);
  std::free(big.release());
}

} // namespace
