// The fan morph's geometry (FanMorph.h): which nodes morph so, the fan's surface at a
// sample, and the node's exact residual and errors for the table.
#include "FanMorph.h"

#include "Levels.h"
#include "RasterError.h"
#include "Tessellate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

namespace gmm
{

bool fanMorphable(const Quadtree& qt, int node)
{
  return mergeableNode(qt, node) && mergedErrorIsExact(qt, node) && !mergeNestsInBlocks(qt, node) &&
    qt.nodeClearOfNodata(node);
}

double fanSurfaceHeight(const Heightfield& hf, const Quadtree& qt, int node, int i, int j)
{
  const QuadtreeNode& n = qt.nodes[node];
  const GridPoint c = mergedCentre(qt, node);
  const double hc = hf.height(c.i, c.j);
  const int dx = i - c.i, dy = j - c.j;
  if (dx == 0 && dy == 0)
  {
    return hc;
  }
  const int i0 = qt.colStart[n.colBegin], i1 = qt.colStart[n.colEnd];
  const int j0 = qt.rowStart[n.rowBegin], j1 = qt.rowStart[n.rowEnd];
  // The ray from the centre through (i, j) leaves the node at centre + s (dx, dy), s >= 1,
  // on the perimeter segment between two block corners; the fan's triangle over that
  // segment is linear along the ray.
  const double inf = std::numeric_limits<double>::infinity();
  const double sx = dx > 0 ? double(i1 - c.i) / dx : dx < 0 ? double(i0 - c.i) / dx : inf;
  const double sy = dy > 0 ? double(j1 - c.j) / dy : dy < 0 ? double(j0 - c.j) / dy : inf;
  const bool vertical = sx <= sy; // leaves through the east or west side
  const double s = std::min(sx, sy);
  const std::vector<int>& start = vertical ? qt.rowStart : qt.colStart;
  const int first = vertical ? n.rowBegin : n.colBegin, last = vertical ? n.rowEnd : n.colEnd;
  const double along = vertical ? c.j + s * dy : c.i + s * dx;
  const int line = vertical ? (dx > 0 ? i1 : i0) : (dy > 0 ? j1 : j0);
  int k = first;
  while (k + 1 < last && start[k + 1] <= along)
  {
    ++k;
  }
  const int a = start[k], b = start[k + 1];
  const double ha = vertical ? hf.height(line, a) : hf.height(a, line);
  const double hb = vertical ? hf.height(line, b) : hf.height(b, line);
  const double hq = ha + (along - a) / (b - a) * (hb - ha);
  return hc + (hq - hc) / s;
}

namespace
{
// Calls visit(i, j, index into the node's rectangle, a, b) for every sample (i, j) that
// triangle t covers (edges included), a and b the values interpolated from two sets given
// at its vertices.
template <typename Visit>
void rasterise(const GridTriangle& t, const std::array<double, 3>& a3, const std::array<double, 3>& b3, int i0,
  int j0, int width, Visit visit)
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

// The node's children at their coarsest, as grid triangles: mergeable child nodes' fans,
// the blocks of the others at their top level (one quad each).
void childrenAtCoarsestGrid(const Quadtree& qt, int node, std::vector<GridTriangle>& out)
{
  const QuadtreeNode& n = qt.nodes[node];
  EmitScratch scratch;
  for (int k = 0; k < n.childCount; ++k)
  {
    const int child = n.firstChild + k;
    if (mergeableNode(qt, child))
    {
      emitMergedNodeGrid(qt, child, out);
      continue;
    }
    const QuadtreeNode& q = qt.nodes[child];
    for (int r = q.rowBegin; r < q.rowEnd; ++r)
    {
      for (int c = q.colBegin; c < q.colEnd; ++c)
      {
        const int b = qt.blockIndex(c, r);
        BlockConfig top;
        top.level = qt.blockTopLevel(b);
        top.edgeLevel = { top.level, top.level, top.level, top.level };
        emitBlockGrid(qt, b, top, BlockPart::Whole, out, scratch);
      }
    }
  }
}
// Every child vertex is a block corner: the heights (less z0) the node's corners are drawn
// at with the children moved onto the fan, row by row from its south-west corner. One
// strictly inside the node is at the fan's height as the frame stores it (a float:
// MorphFrame::cornerTarget); those on the perimeter never move.
void movedCornerHeights(const Heightfield& hf, const Quadtree& qt, int node, double z0, std::vector<double>& out)
{
  const QuadtreeNode& n = qt.nodes[node];
  const int cols = n.colEnd - n.colBegin + 1;
  out.resize(static_cast<std::size_t>(cols) * (n.rowEnd - n.rowBegin + 1));
  for (int r = n.rowBegin; r <= n.rowEnd; ++r)
  {
    for (int c = n.colBegin; c <= n.colEnd; ++c)
    {
      const int i = qt.colStart[c], j = qt.rowStart[r];
      const bool perimeter = r == n.rowBegin || r == n.rowEnd || c == n.colBegin || c == n.colEnd;
      out[static_cast<std::size_t>(r - n.rowBegin) * cols + (c - n.colBegin)] =
        (perimeter ? hf.height(i, j) : static_cast<float>(fanSurfaceHeight(hf, qt, node, i, j))) - z0;
    }
  }
}

// The block grid line through band start s (bandOfSample gives the DEM's last sample to the
// band before it).
int gridLineOf(const std::vector<int>& start, int s)
{
  const int band = bandOfSample(start, s);
  return start[band] == s ? band : band + 1;
}
} // namespace

FanMorphErrors fanMorphErrors(const Heightfield& hf, const Quadtree& qt, int node)
{
  FanMorphScratch scratch;
  return fanMorphErrors(hf, qt, node, scratch);
}

FanMorphErrors fanMorphErrors(const Heightfield& hf, const Quadtree& qt, int node, FanMorphScratch& scratch)
{
  const float inf = std::numeric_limits<float>::infinity();
  if (!fanMorphable(qt, node))
  {
    return { inf, inf, inf };
  }
  const QuadtreeNode& n = qt.nodes[node];
  const int i0 = qt.colStart[n.colBegin], i1 = qt.colStart[n.colEnd];
  const int j0 = qt.rowStart[n.rowBegin], j1 = qt.rowStart[n.rowEnd];
  const int width = i1 - i0 + 1;
  // Heights relative to the fan's centre sample: errors from differences, as the table's.
  const GridPoint centre = mergedCentre(qt, node);
  const double z0 = hf.height(centre.i, centre.j);
  auto own = [&](GridPoint p) { return hf.height(p.i, p.j) - z0; };
  std::vector<double>& fan = scratch.fan;
  fan.resize(static_cast<std::size_t>(width) * (j1 - j0 + 1)); // every sample is written
  std::vector<GridTriangle>& tris = scratch.triangles;
  tris.clear();
  emitMergedNodeGrid(qt, node, tris);
  for (const GridTriangle& t : tris)
  {
    const std::array<double, 3> h{ own(t.v[0]), own(t.v[1]), own(t.v[2]) };
    rasterise(t, h, h, i0, j0, width, [&](int, int, std::size_t s, double f, double) { fan[s] = f; });
  }
  movedCornerHeights(hf, qt, node, z0, scratch.movedCorner);
  const int cols = n.colEnd - n.colBegin + 1;
  auto moved = [&](GridPoint p) {
    const int c = gridLineOf(qt.colStart, p.i), r = gridLineOf(qt.rowStart, p.j);
    return scratch.movedCorner[static_cast<std::size_t>(r - n.rowBegin) * cols + (c - n.colBegin)];
  };
  tris.clear();
  childrenAtCoarsestGrid(qt, node, tris);
  double residual = 0.0, movedError = 0.0, childrenError = 0.0;
  for (const GridTriangle& t : tris)
  {
    const std::array<double, 3> m{ moved(t.v[0]), moved(t.v[1]), moved(t.v[2]) };
    const std::array<double, 3> h{ own(t.v[0]), own(t.v[1]), own(t.v[2]) };
    rasterise(t, m, h, i0, j0, width, [&](int i, int j, std::size_t s, double hm, double hc) {
      const double sample = hf.height(i, j) - z0;
      residual = std::max(residual, std::abs(hm - fan[s]));
      movedError = std::max(movedError, std::abs(hm - sample));
      childrenError = std::max(childrenError, std::abs(hc - sample));
    });
  }
  return { roundUpToFloat(residual), roundUpToFloat(movedError), roundUpToFloat(childrenError) };
}

} // namespace gmm
