#include "VertexPitch.h"

#include "IndexArena.h"

#include <algorithm>

namespace gmm
{

uint32_t drawPitch(int nx, int ny)
{
  const uint64_t width = static_cast<uint64_t>(nx);
  const uint64_t pitch = width + (kDrawPitchResidue + 256u - width % 256u) % 256u;
  const uint64_t lastId = (static_cast<uint64_t>(ny) - 1u) * pitch + (width - 1u);
  return lastId < kRestartIndex ? static_cast<uint32_t>(pitch) : static_cast<uint32_t>(width);
}

void toDrawIds(const uint32_t* in, std::size_t count, int nx, uint32_t pitch, uint32_t* out)
{
  const uint32_t pad = pitch - static_cast<uint32_t>(nx);
  if (pad == 0)
  {
    std::copy(in, in + count, out); // a no-op in place
    return;
  }
  if (nx == 1) // j = v (and m below would be 2^64)
  {
    for (std::size_t k = 0; k < count; ++k)
    {
      out[k] = in[k] == kRestartIndex ? in[k] : in[k] * pitch;
    }
    return;
  }
  // j = v / nx as a multiply-high: m = floor((2^64 - 1) / nx) + 1 = 2^64 / nx + e with
  // 0 < e <= 1, so v m / 2^64 = v / nx + v e / 2^64, and v e / 2^64 < 2^-32 < 1 / nx cannot
  // carry v / nx (whose fraction is at most 1 - 1 / nx) past an integer: exact for every
  // 32-bit v. The high 64 bits of the 96-bit product v m come from m's two 32-bit halves
  // (no term overflows: v m_hi + (v m_lo >> 32) < 2^64 - 2^33 + 1 + 2^32).
  const uint64_t m = UINT64_MAX / static_cast<uint64_t>(nx) + 1u;
  const uint64_t mLo = m & 0xFFFFFFFFu, mHi = m >> 32;
  for (std::size_t k = 0; k < count; ++k)
  {
    const uint64_t v = in[k];
    const uint32_t j = static_cast<uint32_t>((v * mHi + ((v * mLo) >> 32)) >> 32);
    out[k] = in[k] == kRestartIndex ? in[k] : in[k] + j * pad;
  }
}

} // namespace gmm
