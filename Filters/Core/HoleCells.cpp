#include "HoleCells.h"

#include "Levels.h"
#include "Tessellate.h"

#include <algorithm>

namespace gmm
{

namespace
{
// Where a cell side [lo, hi] is split: at the largest power of two below its length from
// lo, which is the next level's sample (lo is a multiple of the cell's level step from the
// block's first sample); hi when it is one quad and is not split.
int splitPoint(int lo, int hi)
{
  const int n = hi - lo;
  if (n < 2)
  {
    return hi;
  }
  int step = 1;
  while (step * 2 < n)
  {
    step *= 2;
  }
  return lo + step;
}

// Appends the cells `cell` splits into (two or four, each with its nodata flag unset).
void splitCell(const HoleCell& cell, std::vector<HoleCell>& out)
{
  const int im = splitPoint(cell.i0, cell.i1), jm = splitPoint(cell.j0, cell.j1);
  const int is[3] = { cell.i0, im, cell.i1 }, js[3] = { cell.j0, jm, cell.j1 };
  for (int b = 0; b < 2; ++b)
  {
    for (int a = 0; a < 2; ++a)
    {
      if (is[a + 1] > is[a] && js[b + 1] > js[b])
      {
        out.push_back({ is[a], js[b], is[a + 1], js[b + 1], false });
      }
    }
  }
}

// Nodata samples in [i0, i1] x [j0, j1] (inclusive), from the summed table.
uint32_t nodataIn(const HoleCells& h, const HoleCell& c)
{
  const std::size_t stride = static_cast<std::size_t>(h.width) + 2;
  const std::size_t x0 = c.i0 - h.i0, x1 = c.i1 - h.i0 + 1, y0 = c.j0 - h.j0, y1 = c.j1 - h.j0 + 1;
  const std::vector<uint32_t>& s = h.nodataBelow;
  return s[y1 * stride + x1] - s[y0 * stride + x1] - s[y1 * stride + x0] + s[y0 * stride + x0];
}

// Whether sample (i, j) of the area is nodata, from the summed table.
bool isNodata(const HoleCells& h, int i, int j)
{
  return nodataIn(h, HoleCell{ i, j, i, j, false }) != 0;
}

// The vertices: every cell's corners, and the block's border where the cells reach it (its
// every sample, as the neighbours' edges have them). A side strip's inner line has the
// cells' corners only: the strip joins them.
void markVertices(HoleCells& h)
{
  const std::size_t w = static_cast<std::size_t>(h.width) + 1;
  h.vertex.assign(w * (static_cast<std::size_t>(h.height) + 1), 0);
  for (std::size_t x = 0; x < w; ++x)
  {
    h.vertex[x] |= h.strip[South] ? 0 : 1;
    h.vertex[h.height * w + x] |= h.strip[North] ? 0 : 1;
  }
  for (int y = 0; y <= h.height; ++y)
  {
    h.vertex[y * w] |= h.strip[West] ? 0 : 1;
    h.vertex[y * w + h.width] |= h.strip[East] ? 0 : 1;
  }
  for (const HoleCell& c : h.cells)
  {
    const std::size_t x0 = c.i0 - h.i0, x1 = c.i1 - h.i0, y0 = c.j0 - h.j0, y1 = c.j1 - h.j0;
    h.vertex[y0 * w + x0] = h.vertex[y0 * w + x1] = h.vertex[y1 * w + x0] = h.vertex[y1 * w + x1] = 1;
  }
}

// Vertices strictly inside each side of a clean cell, in Side order.
void sideVertexCounts(const HoleCells& h, const HoleCell& c, int count[4])
{
  count[South] = count[East] = count[North] = count[West] = 0;
  for (int i = c.i0 + 1; i < c.i1; ++i)
  {
    count[South] += h.isVertex(i, c.j0);
    count[North] += h.isVertex(i, c.j1);
  }
  for (int j = c.j0 + 1; j < c.j1; ++j)
  {
    count[East] += h.isVertex(c.i1, j);
    count[West] += h.isVertex(c.i0, j);
  }
}
} // namespace

void buildHoleCells(const Quadtree& qt, int block, int level, HoleCells& out)
{
  const int c = block % qt.blockCols, r = block / qt.blockCols;
  const int bi0 = qt.colStart[c], bj0 = qt.rowStart[r];
  const int bw = qt.colStart[c + 1] - bi0, bh = qt.rowStart[r + 1] - bj0;
  std::vector<int>& C = out.cols;
  std::vector<int>& R = out.rows;
  edgeSamples(bi0, bi0 + bw, level, C);
  edgeSamples(bj0, bj0 + bh, level, R);
  // The area the cells cover: the block, less the border rows that side strips draw.
  for (int side = South; side <= West; ++side)
  {
    out.strip[side] = qt.sideClearOfNodata(block, side, level);
  }
  const std::size_t firstCol = out.strip[West] ? 1 : 0, lastCol = C.size() - (out.strip[East] ? 2 : 1);
  const std::size_t firstRow = out.strip[South] ? 1 : 0, lastRow = R.size() - (out.strip[North] ? 2 : 1);
  out.blockI0 = bi0;
  out.blockJ0 = bj0;
  out.blockI1 = bi0 + bw;
  out.blockJ1 = bj0 + bh;
  out.i0 = C[firstCol];
  out.j0 = R[firstRow];
  out.width = C[lastCol] - out.i0;
  out.height = R[lastRow] - out.j0;
  out.cells.clear();
  if (qt.everySampleNodata(block))
  {
    // Nothing of it is drawn at any level above 0: no cells (and no triangles to count).
    markVertices(out);
    return;
  }
  // Summed nodata counts over the area: nodataBelow[y][x] counts the nodata samples left of
  // x and below y. The block's nodata bits are read in their order (Quadtree::nodataBits:
  // row by row, borders included), which costs the table build far less than a lookup per
  // sample.
  const std::size_t stride = static_cast<std::size_t>(out.width) + 2;
  out.nodataBelow.assign(stride * (static_cast<std::size_t>(out.height) + 2), 0);
  const uint64_t* bits = qt.nodataBits.data() + qt.nodataBitsAt[block];
  for (int y = 0; y <= out.height; ++y)
  {
    uint32_t row = 0;
    uint64_t bit = static_cast<uint64_t>(out.j0 - bj0 + y) * (bw + 1) + (out.i0 - bi0);
    for (int x = 0; x <= out.width; ++x, ++bit)
    {
      row += static_cast<uint32_t>((bits[bit / 64] >> (bit % 64)) & 1u);
      out.nodataBelow[(y + 1) * stride + x + 1] = out.nodataBelow[y * stride + x + 1] + row;
    }
  }
  // The level's cells, each split down towards its nodata (depth first, so that a cell's
  // pieces stay together in drawing order).
  std::vector<HoleCell>& pending = out.pending;
  pending.clear();
  for (std::size_t b = firstRow; b < lastRow; ++b)
  {
    for (std::size_t a = firstCol; a < lastCol; ++a)
    {
      pending.push_back({ C[a], R[b], C[a + 1], R[b + 1], false });
      while (!pending.empty())
      {
        HoleCell cell = pending.back();
        pending.pop_back();
        if (nodataIn(out, cell) == 0)
        {
          out.cells.push_back(cell);
        }
        else if (cell.i1 - cell.i0 == 1 && cell.j1 - cell.j0 == 1)
        {
          cell.nodata = true;
          out.cells.push_back(cell);
        }
        else
        {
          const std::size_t firstPiece = pending.size();
          splitCell(cell, pending);
          std::reverse(pending.begin() + firstPiece, pending.end()); // south-west piece first
        }
      }
    }
  }
  markVertices(out);
}

void innerRingLine(const HoleCells& cells, int side, std::vector<GridPoint>& out)
{
  out.clear();
  const int i0 = cells.i0, i1 = cells.i0 + cells.width, j0 = cells.j0, j1 = cells.j0 + cells.height;
  switch (side)
  {
    case South:
      for (int i = i0; i <= i1; ++i)
        if (cells.isVertex(i, j0))
          out.push_back({ i, j0 });
      break;
    case East:
      for (int j = j0; j <= j1; ++j)
        if (cells.isVertex(i1, j))
          out.push_back({ i1, j });
      break;
    case North:
      for (int i = i1; i >= i0; --i)
        if (cells.isVertex(i, j1))
          out.push_back({ i, j1 });
      break;
    default: // West
      for (int j = j1; j >= j0; --j)
        if (cells.isVertex(i0, j))
          out.push_back({ i0, j });
      break;
  }
}

void stripEnds(const HoleCells& cells, int side, std::vector<GridPoint>& start, std::vector<GridPoint>& end)
{
  start.clear();
  end.clear();
  const int i0 = cells.i0, i1 = cells.i0 + cells.width, j0 = cells.j0, j1 = cells.j0 + cells.height;
  const int bi0 = cells.blockI0, bi1 = cells.blockI1, bj0 = cells.blockJ0, bj1 = cells.blockJ1;
  const bool before = !cells.strip[(side + 3) % 4], after = !cells.strip[(side + 1) % 4];
  switch (side)
  {
    case South: // start: down the west border at bi0; end: up the east border at bi1
      for (int j = j0; before && j >= bj0; --j)
        start.push_back({ bi0, j });
      for (int j = bj0; after && j <= j0; ++j)
        end.push_back({ bi1, j });
      break;
    case East: // start: east along the south border; end: east along the north border
      for (int i = i1; before && i <= bi1; ++i)
        start.push_back({ i, bj0 });
      for (int i = bi1; after && i >= i1; --i)
        end.push_back({ i, bj1 });
      break;
    case North: // start: up the east border; end: down the west border
      for (int j = j1; before && j <= bj1; ++j)
        start.push_back({ bi1, j });
      for (int j = bj1; after && j >= j1; --j)
        end.push_back({ bi0, j });
      break;
    default: // West: start: west along the north border; end: west along the south border
      for (int i = i0; before && i >= bi0; --i)
        start.push_back({ i, bj1 });
      for (int i = bi0; after && i <= i0; ++i)
        end.push_back({ i, bj0 });
      break;
  }
}

std::size_t holeCellsTriangleCount(const HoleCells& cells)
{
  std::size_t n = 0;
  for (const HoleCell& cell : cells.cells)
  {
    if (cell.nodata)
    {
      // Drawn as at full resolution (TriangleSinks.h, quad, split by
      // fullResolutionAntiDiagonal), less the triangles with a nodata corner, which are
      // dropped.
      const bool sw = isNodata(cells, cell.i0, cell.j0), se = isNodata(cells, cell.i1, cell.j0);
      const bool ne = isNodata(cells, cell.i1, cell.j1), nw = isNodata(cells, cell.i0, cell.j1);
      if (fullResolutionAntiDiagonal(cell.i0, cell.j0))
      {
        n += (sw || se || nw) ? 0 : 1;
        n += (se || ne || nw) ? 0 : 1;
      }
      else
      {
        n += (sw || se || ne) ? 0 : 1;
        n += (sw || ne || nw) ? 0 : 1;
      }
      continue;
    }
    int count[4];
    sideVertexCounts(cells, cell, count);
    n += cellTriangleCount(4 + static_cast<std::size_t>(count[South] + count[East] + count[North] + count[West]));
  }
  // Each side strip's fans take one triangle per step along its inner line, and one per
  // point of an end on the border beyond the inner line's first step (Tessellate.cpp,
  // drawSideLines).
  std::vector<GridPoint> line, start, end;
  for (int side = South; side <= West; ++side)
  {
    if (cells.strip[side])
    {
      innerRingLine(cells, side, line);
      stripEnds(cells, side, start, end);
      n += line.size() - 1;
      n += start.empty() ? 0 : start.size() - 2;
      n += end.empty() ? 0 : end.size() - 2;
    }
  }
  return n;
}

std::size_t fannedCellTriangleCount(int w, int h, const bool fine[4])
{
  std::size_t vertices = 4;
  for (int side = South; side <= West; ++side)
  {
    if (fine[side])
    {
      vertices += static_cast<std::size_t>(side == South || side == North ? w : h) - 1;
    }
  }
  return cellTriangleCount(vertices);
}

} // namespace gmm
