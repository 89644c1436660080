// The strips every tessellation is made of, into any triangle sink (TriangleSinks.h):
// rows of quads (drawHStrip, drawInnerGrid) and the band between two polylines cut into
// fans (drawSideStrip, drawFan: any level to any other). Private to Tessellate.cpp, apart
// from how it assembles a block from them (shapes, nodata cells, which parts).
#pragma once

#include "CellDrawing.h"
#include "GridTypes.h"
#include "Tessellate.h"

#include <vector>

namespace gmm
{

// One row band of the inner grid: quads between rows ja and jb over columns cols[0..count).
template <typename Sink>
void drawHStrip(Sink& sink, const int* cols, std::size_t count, int ja, int jb)
{
  for (std::size_t u = 0; u + 1 < count; ++u)
  {
    sink.quad(cols[u], ja, cols[u + 1], jb);
  }
}

// Inner grid of a ring block: samples cols[1..k-1] x rows[1..L-1] at the block's own step.
template <typename Sink>
void drawInnerGrid(Sink& sink, const std::vector<int>& C, const std::vector<int>& R)
{
  for (std::size_t t = 1; t + 2 < R.size(); ++t)
  {
    drawHStrip(sink, C.data() + 1, C.size() - 2, R[t], R[t + 1]);
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
// block's level), `innerFirst` picks the quad's diagonal: the merge then splits it along
// the same (i, j)-(i+1, j+1) diagonal as the inner grid, so that a block with its own edges
// draws one regular triangulation (at level 0, exactly the full-resolution one).
template <typename Sink, typename Along>
void drawSideStrip(Sink& sink, const std::vector<GridPoint>& outer,
  const std::vector<GridPoint>& inner, std::size_t first, std::size_t last, Along along,
  bool innerFirst)
{
  // True when the outer point at position x is to be joined before the inner one at y.
  auto outerBefore = [innerFirst](int x, int y) { return innerFirst ? x < y : x <= y; };
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
template <typename Sink>
void drawSideLines(Sink& sink, const EmitScratch& lines, int side)
{
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
      drawSideStrip(sink, outer, inner, first, last, [](GridPoint p) { return p.i; }, true);
      break;
    case East:
      drawSideStrip(sink, outer, inner, first, last, [](GridPoint p) { return p.j; }, false);
      break;
    case North:
      drawSideStrip(sink, outer, inner, first, last, [](GridPoint p) { return -p.i; }, true);
      break;
    default: // West
      drawSideStrip(sink, outer, inner, first, last, [](GridPoint p) { return -p.j; }, false);
      break;
  }
}

} // namespace gmm
