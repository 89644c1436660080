// gmm::halfOf against an independent decoding of every half (ldexp): each half's own
// value maps back to it, values between two halves go to the nearer, ties to the even one,
// and the range ends give +-inf, NaN stays NaN.
#include "HalfFloat.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace
{
// The value of a finite half, from its fields.
double valueOf(uint16_t h)
{
  const int sign = (h & 0x8000) ? -1 : 1, exponent = (h >> 10) & 0x1f, mantissa = h & 0x3ff;
  if (exponent == 0)
    return sign * std::ldexp(mantissa, -24);
  return sign * std::ldexp(1024 + mantissa, exponent - 25);
}
} // namespace

TEST(HalfFloat, EveryHalfRoundTripsAndMidpointsTieToEven)
{
  int checked = 0;
  for (uint32_t h = 0; h < 0x7c00; ++h) // every finite non-negative half
  {
    const double v = valueOf(static_cast<uint16_t>(h));
    ASSERT_EQ(gmm::halfOf(static_cast<float>(v)), h) << v;
    ASSERT_EQ(gmm::halfOf(static_cast<float>(-v)), h | 0x8000u) << -v;
    if (h + 1 < 0x7c00)
    {
      const double next = valueOf(static_cast<uint16_t>(h + 1)), mid = 0.5 * (v + next);
      // Midpoints are floats exactly (halves have 11 significant bits, floats 24).
      ASSERT_EQ(static_cast<double>(static_cast<float>(mid)), mid);
      const uint32_t even = (h & 1u) ? h + 1 : h;
      ASSERT_EQ(gmm::halfOf(static_cast<float>(mid)), even) << "tie at " << mid;
      ASSERT_EQ(gmm::halfOf(std::nextafter(static_cast<float>(mid), 0.0f)), h) << mid;
      ASSERT_EQ(gmm::halfOf(std::nextafter(static_cast<float>(mid), 1e9f)), h + 1) << mid;
    }
    ++checked;
  }
  EXPECT_EQ(checked, 0x7c00);
}

TEST(HalfFloat, RangeEndsAndSpecials)
{
  EXPECT_EQ(gmm::halfOf(65504.0f), 0x7bffu);                      // largest half
  EXPECT_EQ(gmm::halfOf(std::nextafter(65520.0f, 0.0f)), 0x7bffu); // just below the tie
  EXPECT_EQ(gmm::halfOf(65520.0f), 0x7c00u);                      // the tie rounds to inf
  EXPECT_EQ(gmm::halfOf(1e30f), 0x7c00u);
  EXPECT_EQ(gmm::halfOf(-1e30f), 0xfc00u);
  EXPECT_EQ(gmm::halfOf(std::numeric_limits<float>::infinity()), 0x7c00u);
  EXPECT_EQ(gmm::halfOf(-std::numeric_limits<float>::infinity()), 0xfc00u);
  EXPECT_EQ(gmm::halfOf(std::numeric_limits<float>::quiet_NaN()) & 0x7e00u, 0x7e00u);
  EXPECT_EQ(gmm::halfOf(-0.0f), 0x8000u);
  EXPECT_EQ(gmm::halfOf(std::ldexp(1.0f, -26)), 0u);  // below half the smallest subnormal
  EXPECT_EQ(gmm::halfOf(std::ldexp(1.5f, -25)), 1u);  // above it
  EXPECT_EQ(gmm::halfOf(1e-30f), 0u);
}
