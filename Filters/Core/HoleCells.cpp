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

// The vertices: every cell's corners and the block's border.
void markVertices(HoleCells& h)
{
  const std::size_t w = static_cast<std::size_t>(h.width) + 1;
  h.vertex.assign(w * (static_cast<std::size_t>(h.height) + 1), 0);
  for (std::size_t x = 0; x < w; ++x)
  {
    h.vertex[x] = h.vertex[h.height * w + x] = 1;
  }
  for (int y = 0; y <= h.height; ++y)
  {
    h.vertex[y * w] = h.vertex[y * w + h.width] = 1;
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
  out.i0 = qt.colStart[c];
  out.j0 = qt.rowStart[r];
  out.width = qt.colStart[c + 1] - out.i0;
  out.height = qt.rowStart[r + 1] - out.j0;
  out.cells.clear();
  if (qt.everySampleNodata(block))
  {
    // Nothing of it is drawn at any level above 0: no cells (and no triangles to count).
    markVertices(out);
    return;
  }
  // Summed nodata counts: nodataBelow[y][x] counts the nodata samples left of x and below y.
  // The block's nodata bits are read in their order (Quadtree::nodataBits: row by row,
  // borders included), which costs the table build far less than a lookup per sample.
  const std::size_t stride = static_cast<std::size_t>(out.width) + 2;
  out.nodataBelow.assign(stride * (static_cast<std::size_t>(out.height) + 2), 0);
  const uint64_t* bits = qt.nodataBits.data() + qt.nodataBitsAt[block];
  uint64_t bit = 0;
  for (int y = 0; y <= out.height; ++y)
  {
    uint32_t row = 0;
    for (int x = 0; x <= out.width; ++x, ++bit)
    {
      row += static_cast<uint32_t>((bits[bit / 64] >> (bit % 64)) & 1u);
      out.nodataBelow[(y + 1) * stride + x + 1] = out.nodataBelow[y * stride + x + 1] + row;
    }
  }
  // The level's cells, each split down towards its nodata (depth first, so that a cell's
  // pieces stay together in drawing order).
  std::vector<int>& C = out.cols;
  std::vector<int>& R = out.rows;
  edgeSamples(out.i0, out.i0 + out.width, level, C);
  edgeSamples(out.j0, out.j0 + out.height, level, R);
  std::vector<HoleCell>& pending = out.pending;
  pending.clear();
  for (std::size_t b = 0; b + 1 < R.size(); ++b)
  {
    for (std::size_t a = 0; a + 1 < C.size(); ++a)
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
          const std::size_t first = pending.size();
          splitCell(cell, pending);
          std::reverse(pending.begin() + first, pending.end()); // south-west piece first
        }
      }
    }
  }
  markVertices(out);
}

std::size_t holeCellsTriangleCount(const HoleCells& cells)
{
  std::size_t n = 0;
  for (const HoleCell& cell : cells.cells)
  {
    if (cell.nodata)
    {
      n += 2;
      continue;
    }
    int count[4];
    sideVertexCounts(cells, cell, count);
    n += cellTriangleCount(4 + static_cast<std::size_t>(count[South] + count[East] + count[North] + count[West]));
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

bool oneQuadFineSides(const Quadtree& qt, int block, bool fine[4])
{
  bool any = false;
  for (int side = South; side <= West; ++side)
  {
    fine[side] = qt.sideAtFullResolution(block, side);
    any = any || fine[side];
  }
  return any && qt.blockWidth(block) >= 2 && qt.blockHeight(block) >= 2;
}

} // namespace gmm
