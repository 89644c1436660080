// Rasterising a fan's long, thin triangles over the full-resolution samples they cover,
// with values interpolated from their vertices: the fan morph's tables (FanMorph.h) and the
// coarse perimeters' (CoarsePerimeter.h) compare surfaces sample by sample with it.
#pragma once

#include "GridTypes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

namespace gmm
{

// Calls visit(i, j, index into the node's rectangle, a, b) for every sample (i, j) that
// triangle t covers (edges included), a and b the values interpolated from two sets given
// at its vertices.
template <typename Visit>
void rasteriseFanTriangle(const GridTriangle& t, const std::array<double, 3>& a3,
  const std::array<double, 3>& b3, int i0, int j0, int width, Visit visit)
{
  const GridPoint a = t.v[0], b = t.v[1], c = t.v[2];
  const int64_t area = int64_t(b.i - a.i) * (c.j - a.j) - int64_t(b.j - a.j) * (c.i - a.i);
  if (area == 0)
  {
    return;
  }
  const double inv = 1.0 / std::abs(static_cast<double>(area));
  const int64_t sign = area > 0 ? 1 : -1;
  const int loI = std::min({ a.i, b.i, c.i }), hiI = std::max({ a.i, b.i, c.i });
  const int loJ = std::min({ a.j, b.j, c.j }), hiJ = std::max({ a.j, b.j, c.j });
  const std::array<GridPoint, 3> v{ a, b, c };
  for (int j = loJ; j <= hiJ; ++j)
  {
    // The row's span within the triangle, widened by a sample (the inside test decides):
    // fans' triangles are long and thin, and their bounding boxes a node's area each.
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (int k = 0; k < 3; ++k)
    {
      const GridPoint p = v[k], q = v[(k + 1) % 3];
      if (p.j == q.j ? p.j == j : (j - p.j) * int64_t(j - q.j) <= 0)
      {
        const double x = p.j == q.j ? p.i : p.i + double(j - p.j) * (q.i - p.i) / (q.j - p.j);
        const double y = p.j == q.j ? q.i : x;
        lo = std::min({ lo, x, y });
        hi = std::max({ hi, x, y });
      }
    }
    const int first = std::max(loI, static_cast<int>(std::floor(lo)) - 1);
    const int last = std::min(hiI, static_cast<int>(std::ceil(hi)) + 1);
    for (int i = first; i <= last; ++i)
    {
      const int64_t w0 = sign * (int64_t(b.i - i) * (c.j - j) - int64_t(b.j - j) * (c.i - i));
      const int64_t w1 = sign * (int64_t(c.i - i) * (a.j - j) - int64_t(c.j - j) * (a.i - i));
      const int64_t w2 = sign * (int64_t(a.i - i) * (b.j - j) - int64_t(a.j - j) * (b.i - i));
      if (w0 >= 0 && w1 >= 0 && w2 >= 0)
      {
        visit(i, j, static_cast<std::size_t>(j - j0) * width + (i - i0), (w0 * a3[0] + w1 * a3[1] + w2 * a3[2]) * inv,
          (w0 * b3[0] + w1 * b3[1] + w2 * b3[2]) * inv);
      }
    }
  }
}

} // namespace gmm
