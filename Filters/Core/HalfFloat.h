// IEEE 754 binary16 ("half") from a float, for textures stored as half floats.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>

namespace gmm
{

// The half nearest to f, ties to even, as a GL implementation converts it: +-inf beyond
// the half range (|f| >= 65520), NaN kept NaN (quiet), subnormal halves below 2^-14.
inline uint16_t halfOf(float f)
{
  uint32_t x;
  std::memcpy(&x, &f, sizeof x);
  const uint32_t sign = (x >> 16) & 0x8000u, a = x & 0x7fffffffu;
  if (a >= 0x7f800000u)
  {
    return static_cast<uint16_t>(sign | (a > 0x7f800000u ? 0x7e00u : 0x7c00u));
  }
  if (a >= 0x477ff000u) // 65520 and above round to infinity
  {
    return static_cast<uint16_t>(sign | 0x7c00u);
  }
  if (a < 0x38800000u) // below 2^-14: a subnormal half (or zero), in units of 2^-24
  {
    float magnitude;
    std::memcpy(&magnitude, &a, sizeof magnitude);
    // Exact scaling by a power of two, then one rounding (the default mode: to even).
    return static_cast<uint16_t>(sign | static_cast<uint32_t>(std::nearbyint(magnitude * 16777216.0f)));
  }
  // Normal: drop 13 mantissa bits rounding to nearest even, and rebias the exponent
  // (127 - 15 = 112); a carry out of the mantissa correctly bumps the exponent.
  const uint32_t rounded = a + 0x0fffu + ((a >> 13) & 1u);
  return static_cast<uint16_t>(sign | ((rounded - (112u << 23)) >> 13));
}

} // namespace gmm
