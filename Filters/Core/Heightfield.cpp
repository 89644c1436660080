#include "Heightfield.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace gmm
{

std::string validateHeightfield(const Heightfield& hf)
{
  std::ostringstream why;
  if (hf.nx < 2 || hf.ny < 2)
  {
    why << "heightfield is " << hf.nx << " x " << hf.ny << " samples; at least 2 x 2 are needed";
    return why.str();
  }
  // Vertex indices are uint32: the largest index must fit.
  const unsigned long long count = static_cast<unsigned long long>(hf.nx) * hf.ny;
  if (count > std::numeric_limits<uint32_t>::max())
  {
    why << "heightfield has " << count << " samples; at most 2^32 - 1 can be indexed";
    return why.str();
  }
  if (hf.external == nullptr && hf.z.size() != count)
  {
    why << "heightfield holds " << hf.z.size() << " heights for " << hf.nx << " x " << hf.ny
        << " = " << count << " samples";
    return why.str();
  }
  if (!std::isfinite(hf.dx) || !std::isfinite(hf.dy) || hf.dx == 0.0 || hf.dy == 0.0)
  {
    why << "spacing (" << hf.dx << ", " << hf.dy << ") must be finite and non-zero";
    return why.str();
  }
  if (!std::isfinite(hf.x0) || !std::isfinite(hf.y0) || !std::isfinite(hf.z0))
  {
    why << "origin (" << hf.x0 << ", " << hf.y0 << ", " << hf.z0 << ") must be finite";
    return why.str();
  }
  const double extentX = std::abs(hf.dx) * (hf.nx - 1), extentY = std::abs(hf.dy) * (hf.ny - 1);
  if (!std::isfinite(extentX) || !std::isfinite(extentY))
  {
    why << "spacing (" << hf.dx << ", " << hf.dy << ") times size " << hf.nx << " x " << hf.ny
        << " overflows";
    return why.str();
  }
  const float* z = hf.heights();
  for (std::size_t k = 0; k < count; ++k)
  {
    const float h = z[k];
    if (std::isfinite(h) && std::abs(h) > kMaxHeight)
    {
      why << "height " << h << " at sample (" << k % hf.nx << ", " << k / hf.nx
          << ") is beyond +-" << kMaxHeight << " m; is it an undeclared nodata value?";
      return why.str();
    }
  }
  return std::string();
}

std::size_t infinitiesToNodata(Heightfield& hf)
{
  if (hf.external)
  {
    const float* begin = hf.external;
    const float* end = begin + hf.sampleCount();
    if (std::none_of(begin, end, [](float h) { return std::isinf(h); }))
    {
      return 0;
    }
    hf.z.assign(begin, end); // never write into storage we do not own
    hf.external = nullptr;
    hf.owner.reset();
  }
  std::size_t replaced = 0;
  for (float& h : hf.z)
  {
    if (std::isinf(h))
    {
      h = std::numeric_limits<float>::quiet_NaN();
      ++replaced;
    }
  }
  return replaced;
}

} // namespace gmm
