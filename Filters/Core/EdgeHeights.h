// The heights a drawn block gives the samples of its border, and the polylines they lie on.
//
// A block edge is drawn as the polyline through its samples at its edge level (the coarser
// of its two blocks, Tessellate.h). On a glided edge (BlockConfig::sampleLevel) the finer
// block's samples between that level's are vertices too: each is drawn on the polyline,
// not at its own height, so that both blocks draw the same line and the finer block's
// cells nest in its next level (Documentation/decisions/002-levels-that-nest.md). Every
// other vertex is drawn at its sample's height. Geomorphing then moves edge vertices from
// these heights toward the polyline at the edge's target (Morph.h).
#pragma once

#include "GridTypes.h"
#include "Heightfield.h"

#include <algorithm>
#include <array>

namespace gmm
{

// Height of the polyline through the samples of [first, last] at `level` (edgeSamples,
// Levels.h), at sample s on that line; `at(k)` gives the height of sample k along the line.
// A sample of that level is its own height.
template <typename At>
double polylineAt(int first, int last, int level, int s, At at)
{
  const long long step = 1LL << level;
  const long long lo = first + (s - first) / step * step;
  if (lo == s)
  {
    return at(s);
  }
  const long long hi = std::min<long long>(lo + step, last);
  const double w = static_cast<double>(s - lo) / static_cast<double>(hi - lo);
  const double a = at(static_cast<int>(lo)), b = at(static_cast<int>(hi));
  return a + w * (b - a);
}

// The side of block rectangle [i0, i1] x [j0, j1] that sample (i, j) lies on, -1 for the
// block's interior and its corners (which are samples of every level).
inline int borderSideOf(int i0, int i1, int j0, int j1, int i, int j)
{
  const bool onV = i == i0 || i == i1, onH = j == j0 || j == j1;
  if (onV == onH)
  {
    return -1;
  }
  return onH ? (j == j0 ? South : North) : (i == i0 ? West : East);
}

// Height of the polyline at `level` through the samples [first, last] of a grid line (row
// `line` when `rows`, else column `line`), at sample s along it.
inline double linePolylineAt(const Heightfield& hf, bool rows, int line, int first, int last, int level, int s)
{
  if (rows)
  {
    return polylineAt(first, last, level, s, [&hf, line](int k) { return double(hf.height(k, line)); });
  }
  return polylineAt(first, last, level, s, [&hf, line](int k) { return double(hf.height(line, k)); });
}

// Height of the polyline of `side` of block rectangle [i0, i1] x [j0, j1] at `level`, at
// sample (i, j) of that side.
inline double sidePolylineAt(const Heightfield& hf, int i0, int i1, int j0, int j1, int side, int level, int i, int j)
{
  return side == South || side == North ? linePolylineAt(hf, true, j, i0, i1, level, i)
                                        : linePolylineAt(hf, false, i, j0, j1, level, j);
}

// The height a block drawn with edge levels `edgeLevel` gives sample (i, j) before
// morphing: on a side (corners excluded) the side's polyline at its edge level, elsewhere
// the sample's own height. A sample at the edge level is on its polyline; a glided one is
// moved onto it.
inline double sideBaseHeight(const Heightfield& hf, int i0, int i1, int j0, int j1,
  const std::array<int, 4>& edgeLevel, int i, int j)
{
  const int side = borderSideOf(i0, i1, j0, j1, i, j);
  if (side < 0 || edgeLevel[side] <= 0)
  {
    return hf.height(i, j);
  }
  return sidePolylineAt(hf, i0, i1, j0, j1, side, edgeLevel[side], i, j);
}

} // namespace gmm
