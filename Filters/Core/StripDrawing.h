// The strips every tessellation is made of, into any triangle sink (TriangleSinks.h):
// rows of quads (drawHStrip, drawInnerGrid) and the band between two polylines cut into
// fans (drawSideStrip, drawFan: any level to any other). Private to Tessellate.cpp, apart
// from how it assembles a block from them (shapes, nodata cells, which parts).
#pragma once

#include "CellDrawing.h"
#include "GridTypes.h"
#include "Levels.h"
#include "Tessellate.h"

#include <vector>

namespace gmm
{

// One row band of the inner grid: quads between rows ja and jb over columns cols[0..count),
// the first of them cell (u0, v) of the block's level grid, each split by the union-jack
// rule (cellAntiDiagonal, Levels.h).
template <typename Sink>
void drawHStrip(Sink& sink, const int* cols, std::size_t count, int ja, int jb, int u0, int v)
{
  for (std::size_t u = 0; u + 1 < count; ++u)
  {
    sink.quad(cols[u], ja, cols[u + 1], jb, cellAntiDiagonal(u0 + static_cast<int>(u), v));
  }
}

// Inner grid of a ring block: samples cols[1..k-1] x rows[1..L-1] at the block's own step,
// cells (1, 1) .. (k - 2, L - 2) of its level grid.
template <typename Sink>
void drawInnerGrid(Sink& sink, const std::vector<int>& C, const std::vector<int>& R)
{
  for (std::size_t t = 1; t + 2 < R.size(); ++t)
  {
    drawHStrip(sink, C.data() + 1, C.size() - 2, R[t], R[t + 1], 1, static_cast<int>(t));
  }
}

// Fan from `apex` over consecutive points run[first..last], which lie on the line opposite
// the apex. apexOnOuter says which side of the strip the apex is on, to keep CCW order.
template <typename Sink>
void drawFan(Sink& sink, GridPoint apex, const std::vector<GridPoint>& run,
  std::size_t first, std::size_t last, bool apexOnOuter)
{
  for (std::size_t k = first; k < last; ++k)
  {
    if (apexOnOuter)
    {
      sink.triangle(apex, run[k + 1], run[k]); // (o_a, in_{b+1}, in_b)
    }
    else
    {
      sink.triangle(run[k], run[k + 1], apex); // (o_a, o_{a+1}, in_b)
    }
  }
}

// Joins the edge polyline (outer) to the inner ring polyline (inner[first..last]) of one
// side. Both run in the block's counter-clockwise direction; `along` gives each point's
// position along the side. The merge advances whichever polyline's next point comes first,
// which cuts the strip into alternating fans: any edge level joins any inner level. When
// the next outer and inner points are level (a regular quad, as when both sides have the
// block's level), `innerFirstAt(x)`, x the quad's far end along the side, picks the quad's
// diagonal: the merge then splits it as the inner grid splits its cells (the union-jack
// rule), so that a block with its own edges draws one regular triangulation.
template <typename Sink, typename Along, typename InnerFirstAt>
void drawSideStrip(Sink& sink, const std::vector<GridPoint>& outer,
  const std::vector<GridPoint>& inner, std::size_t first, std::size_t last, Along along,
  InnerFirstAt innerFirstAt)
{
  // True when the outer point at position x is to be joined before the inner one at y.
  auto outerBefore = [&innerFirstAt](int x, int y) { return x < y || (x == y && !innerFirstAt(x)); };
  std::size_t a = 0, b = first;
  while (a + 1 < outer.size() || b < last)
  {
    const bool advanceOuter = b >= last ||
      (a + 1 < outer.size() && outerBefore(along(outer[a + 1]), along(inner[b + 1])));
    if (advanceOuter)
    {
      std::size_t end = a + 1;
      while (end + 1 < outer.size() && (b >= last || outerBefore(along(outer[end + 1]), along(inner[b + 1]))))
      {
        ++end;
      }
      drawFan(sink, inner[b], outer, a, end, false);
      a = end;
    }
    else
    {
      std::size_t end = b + 1;
      while (end < last && (a + 1 < outer.size() && !outerBefore(along(outer[a + 1]), along(inner[end + 1]))))
      {
        ++end;
      }
      if (a + 1 >= outer.size())
      {
        end = last;
      }
      drawFan(sink, outer[a], inner, b, end, true);
      b = end;
    }
  }
}

// The strip of one side between its two polylines (sideLines), each side's direction
// along the border and diagonal choice. A strip that ends on the block's border (a block
// with nodata whose neighbouring side has no strip, HoleCells.h) first fans that end's
// border samples from the inner line's second (second-last) point, and joins the rest.
// A regular quad of the strip is cell (u, v) of the block's level grid (lines.ring): the
// merge takes the inner point first, which splits it on its (i0, j0)-(i1, j1) diagonal on
// the south and north sides and on the other one on the east and west sides, unless
// cellAntiDiagonal turns it.
template <typename Sink>
void drawSideLines(Sink& sink, const EmitScratch& lines, int side)
{
  const RingGrid& g = lines.ring;
  const int step = 1 << g.level;
  // The cell under a regular quad whose far end along the side is at x (its along value).
  auto cellBefore = [step](int x, int origin) { return (x - origin + step - 1) / step - 1; };
  auto cellFrom = [step](int x, int origin) { return (x - origin) / step; };
  const std::vector<GridPoint>& outer = lines.outer;
  const std::vector<GridPoint>& inner = lines.inner;
  std::size_t first = 0, last = inner.size() - 1;
  if (!lines.stripStart.empty())
  {
    for (std::size_t k = 0; k + 1 < lines.stripStart.size(); ++k)
      triangleCCW(sink, inner[1], lines.stripStart[k], lines.stripStart[k + 1]);
    first = 1;
  }
  if (!lines.stripEnd.empty())
  {
    for (std::size_t k = 0; k + 1 < lines.stripEnd.size(); ++k)
      triangleCCW(sink, inner[last - 1], lines.stripEnd[k], lines.stripEnd[k + 1]);
    last -= 1;
  }
  switch (side)
  {
    case South:
      drawSideStrip(sink, outer, inner, first, last, [](GridPoint p) { return p.i; },
        [&](int x) { return !cellAntiDiagonal(cellBefore(x, g.i0), 0); });
      break;
    case East:
      drawSideStrip(sink, outer, inner, first, last, [](GridPoint p) { return p.j; },
        [&](int x) { return cellAntiDiagonal(g.cellsU - 1, cellBefore(x, g.j0)); });
      break;
    case North:
      drawSideStrip(sink, outer, inner, first, last, [](GridPoint p) { return -p.i; },
        [&](int x) { return !cellAntiDiagonal(cellFrom(-x, g.i0), g.cellsV - 1); });
      break;
    default: // West
      drawSideStrip(sink, outer, inner, first, last, [](GridPoint p) { return -p.j; },
        [&](int x) { return cellAntiDiagonal(0, cellFrom(-x, g.j0)); });
      break;
  }
}

} // namespace gmm
