// Drawing the cells of a block with nodata (HoleCells.h) and the one-quad blocks beside
// one, into any triangle sink (TriangleSinks.h): private to Tessellate.cpp, apart from it
// because it is its own concern (cells over their vertices, not strips between levels).
#pragma once

#include "HoleCells.h"
#include "Levels.h"
#include "Tessellate.h"

#include <algorithm>
#include <vector>

namespace gmm
{

// Emits triangle (a, b, c) counter-clockwise in (i, j), whichever order it is given in.
template <typename Sink>
void triangleCCW(Sink& sink, GridPoint a, GridPoint b, GridPoint c)
{
  const long long cross = static_cast<long long>(b.i - a.i) * (c.j - a.j) -
    static_cast<long long>(b.j - a.j) * (c.i - a.i);
  if (cross > 0)
    sink.triangle(a, b, c);
  else
    sink.triangle(a, c, b);
}

// The quad between two opposite sides that both have points between their corners:
// `lower` and `upper` run along them in the same direction, `first` is the side that joins
// lower[0] to upper[0] and `last` the one that joins their last points (each from the
// lower side's corner to the upper side's, corners included). A side between them with
// points inside is fanned from the lower (first) or upper (last) side's nearest inner
// point; the rest is a strip that zigzags between the two sides. Every triangle has two
// points on one line and one on another, so none is degenerate, and there are two fewer
// than points (a fan from the centre would draw two more).
template <typename Sink, typename Along>
void drawBetweenSides(Sink& sink, const std::vector<GridPoint>& lower,
  const std::vector<GridPoint>& upper, const std::vector<GridPoint>& first,
  const std::vector<GridPoint>& last, Along along)
{
  std::size_t a = 0, b = 0, aEnd = lower.size() - 1, bEnd = upper.size() - 1;
  if (first.size() > 2)
  {
    for (std::size_t k = 0; k + 1 < first.size(); ++k)
      triangleCCW(sink, lower[1], first[k], first[k + 1]);
    a = 1;
  }
  if (last.size() > 2)
  {
    for (std::size_t k = 0; k + 1 < last.size(); ++k)
      triangleCCW(sink, upper[bEnd - 1], last[k], last[k + 1]);
    --bEnd;
  }
  while (a < aEnd || b < bEnd)
  {
    if (b == bEnd || (a < aEnd && along(lower[a + 1]) <= along(upper[b + 1])))
    {
      triangleCCW(sink, lower[a], lower[a + 1], upper[b]);
      ++a;
    }
    else
    {
      triangleCCW(sink, lower[a], upper[b + 1], upper[b]);
      ++b;
    }
  }
}

// The quad [i0, i1] x [j0, j1] over its perimeter (counter-clockwise from its south-west
// corner, each corner once), `fine` saying which sides have points between their corners,
// in two fewer triangles than points: a fan from a corner between two sides without
// (HoleCells.h, coarseCorner), else (two opposite sides have points) drawBetweenSides.
template <typename Sink>
void drawCellPerimeter(Sink& sink, int i0, int j0, int i1, int j1, const bool fine[4],
  const std::vector<GridPoint>& perimeter, EmitSides& sides)
{
  const int corner = coarseCorner(fine);
  if (corner >= 0)
  {
    // From that corner: every other perimeter point lies on a side away from it.
    const GridPoint apex = corner == 0 ? GridPoint{ i0, j0 } : corner == 1 ? GridPoint{ i1, j0 }
      : corner == 2 ? GridPoint{ i1, j1 } : GridPoint{ i0, j1 };
    std::size_t at = 0;
    while (perimeter[at].i != apex.i || perimeter[at].j != apex.j)
      ++at;
    const std::size_t n = perimeter.size();
    for (std::size_t k = 1; k + 1 < n; ++k)
    {
      sink.triangle(apex, perimeter[(at + k) % n], perimeter[(at + k + 1) % n]);
    }
    return;
  }
  // Each side's points, in increasing i (South, North) or j (West, East), corners included.
  for (auto& side : sides.points)
    side.clear();
  for (const GridPoint& p : perimeter)
  {
    if (p.j == j0)
      sides.points[South].push_back(p);
    if (p.j == j1)
      sides.points[North].push_back(p);
    if (p.i == i0)
      sides.points[West].push_back(p);
    if (p.i == i1)
      sides.points[East].push_back(p);
  }
  auto byI = [](GridPoint p, GridPoint q) { return p.i < q.i; };
  auto byJ = [](GridPoint p, GridPoint q) { return p.j < q.j; };
  std::sort(sides.points[South].begin(), sides.points[South].end(), byI);
  std::sort(sides.points[North].begin(), sides.points[North].end(), byI);
  std::sort(sides.points[West].begin(), sides.points[West].end(), byJ);
  std::sort(sides.points[East].begin(), sides.points[East].end(), byJ);
  if (fine[South] && fine[North])
  {
    drawBetweenSides(sink, sides.points[South], sides.points[North], sides.points[West],
      sides.points[East], [](GridPoint p) { return p.i; });
  }
  else
  {
    drawBetweenSides(sink, sides.points[West], sides.points[East], sides.points[South],
      sides.points[North], [](GridPoint p) { return p.j; });
  }
}

// The quad [i0, i1] x [j0, j1] (at least 2 quads either way) over its perimeter, which has
// every sample along the sides marked fine (in Side order) and only the corners elsewhere
// (a one-quad block beside nodata, HoleCells.h).
template <typename Sink>
void drawCellFan(Sink& sink, int i0, int j0, int i1, int j1, const bool fine[4],
  std::vector<GridPoint>& perimeter, EmitSides& sides)
{
  perimeter.clear();
  for (int i = i0; i < i1; i += fine[South] ? 1 : i1 - i0)
    perimeter.push_back({ i, j0 });
  for (int j = j0; j < j1; j += fine[East] ? 1 : j1 - j0)
    perimeter.push_back({ i1, j });
  for (int i = i1; i > i0; i -= fine[North] ? 1 : i1 - i0)
    perimeter.push_back({ i, j1 });
  for (int j = j1; j > j0; j -= fine[West] ? 1 : j1 - j0)
    perimeter.push_back({ i0, j });
  drawCellPerimeter(sink, i0, j0, i1, j1, fine, perimeter, sides);
}

// A ring block with nodata, cell by cell over its whole extent (HoleCells.h): quads with a
// nodata corner as at full resolution, cells with no vertex but their corners as two
// triangles on their (i0, j0)-(i1, j1) diagonal (a block with nodata never morphs, so its
// coarse cells need not nest), the others over their vertices (drawCellPerimeter).
template <typename Sink>
void drawAreaAroundHoles(Sink& sink, const HoleCells& cells, std::vector<GridPoint>& perimeter,
  EmitSides& sides)
{
  for (const HoleCell& c : cells.cells)
  {
    if (c.nodata)
    {
      sink.quad(c.i0, c.j0, c.i1, c.j1, fullResolutionAntiDiagonal(c.i0, c.j0)); // as level 0 draws it
      continue;
    }
    // Counter-clockwise from the south-west corner, each corner once; a side has vertices
    // inside when its run holds more than its first corner.
    perimeter.clear();
    std::size_t start = 0;
    bool inside[4];
    for (int i = c.i0; i < c.i1; ++i)
      if (i == c.i0 || cells.isVertex(i, c.j0))
        perimeter.push_back({ i, c.j0 });
    inside[South] = perimeter.size() - start > 1;
    start = perimeter.size();
    for (int j = c.j0; j < c.j1; ++j)
      if (j == c.j0 || cells.isVertex(c.i1, j))
        perimeter.push_back({ c.i1, j });
    inside[East] = perimeter.size() - start > 1;
    start = perimeter.size();
    for (int i = c.i1; i > c.i0; --i)
      if (i == c.i1 || cells.isVertex(i, c.j1))
        perimeter.push_back({ i, c.j1 });
    inside[North] = perimeter.size() - start > 1;
    start = perimeter.size();
    for (int j = c.j1; j > c.j0; --j)
      if (j == c.j1 || cells.isVertex(c.i0, j))
        perimeter.push_back({ c.i0, j });
    inside[West] = perimeter.size() - start > 1;
    if (perimeter.size() == 4)
    {
      sink.quad(c.i0, c.j0, c.i1, c.j1); // only its corners: two triangles
      continue;
    }
    drawCellPerimeter(sink, c.i0, c.j0, c.i1, c.j1, inside, perimeter, sides);
  }
}

} // namespace gmm
