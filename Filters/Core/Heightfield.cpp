#include "Heightfield.h"

#include "Parallel.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <sstream>

namespace gmm
{

namespace
{
constexpr std::size_t kScanChunk = std::size_t(1) << 20; // samples per chunk (4 MiB)
}

std::string validateHeightfield(const Heightfield& hf, int threads)
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
  // The first sample beyond the range, over chunks scanned in parallel: each chunk's first
  // offender, the smallest index kept.
  const float* z = hf.heights();
  std::atomic<std::size_t> first{ count };
  parallelChunks(count, kScanChunk, threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end && k < first.load(std::memory_order_relaxed); ++k)
    {
      const float h = z[k];
      if (std::isfinite(h) && std::abs(h) > kMaxHeight)
      {
        std::size_t seen = first.load();
        while (k < seen && !first.compare_exchange_weak(seen, k))
        {
        }
        return;
      }
    }
  });
  const std::size_t k = first.load();
  if (k < count)
  {
    why << "height " << z[k] << " at sample (" << k % hf.nx << ", " << k / hf.nx
        << ") is beyond +-" << kMaxHeight << " m; is it an undeclared nodata value?";
    return why.str();
  }
  return std::string();
}

std::size_t infinitiesToNodata(Heightfield& hf, int threads)
{
  // Almost every DEM has none: find out on all cores, then replace on one.
  const float* z = hf.heights();
  std::atomic<bool> any{ false };
  parallelChunks(hf.sampleCount(), kScanChunk, threads, [&](std::size_t begin, std::size_t end) {
    if (!any.load(std::memory_order_relaxed) && std::any_of(z + begin, z + end, [](float h) { return std::isinf(h); }))
    {
      any = true;
    }
  });
  if (!any)
  {
    return 0;
  }
  if (hf.external)
  {
    hf.z.assign(hf.external, hf.external + hf.sampleCount()); // never write into storage we do not own
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
