#include "TriangleCount.h"

#include "HoleCells.h"
#include "Levels.h"

#include <array>
#include <vector>

namespace gmm
{

std::size_t blockTriangleCount(const Quadtree& qt, int block, const BlockConfig& config)
{
  const int c = block % qt.blockCols, r = block / qt.blockCols;
  const int i0 = qt.colStart[c], i1 = qt.colStart[c + 1];
  const int j0 = qt.rowStart[r], j1 = qt.rowStart[r + 1];
  const int w = i1 - i0, h = j1 - j0;
  switch (blockShape(w, h, config.level))
  {
    case BlockShape::OneQuad:
      return 2;
    case BlockShape::Thin:
      return 2 * static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
    case BlockShape::Ring:
      break;
    default:
      return 0;
  }
  // Ring (Tessellate.h): samples C (columns) x R (rows) at the block's level; the inner
  // grid has (|C| - 3) x (|R| - 3) quads, and a side strip's fans emit one triangle per
  // step along either polyline: (edge samples - 1) + (inner ring samples - 1).
  const std::size_t nc = static_cast<std::size_t>(edgeSampleCount(i0, i1, config.level));
  const std::size_t nr = static_cast<std::size_t>(edgeSampleCount(j0, j1, config.level));
  std::size_t n = 2 * (nc - 3) * (nr - 3);
  // Cells around nodata may be drawn at full resolution (HoleCells.h), and the inner ring
  // then has every sample along those beside it.
  std::array<std::size_t, 4> innerExtra{ 0, 0, 0, 0 };
  if (config.level > 0 && qt.blockHasNodata[block])
  {
    std::vector<int> C, R;
    std::vector<CellKind> kind;
    edgeSamples(i0, i1, config.level, C);
    edgeSamples(j0, j1, config.level, R);
    classifyHoleCells(qt, block, C, R, kind);
    if (!kind.empty())
    {
      n = holeCellsTriangleCount(C, R, kind);
      for (int side = South; side <= West; ++side)
      {
        innerExtra[side] = innerRingExtraSamples(C, R, kind, side);
      }
    }
  }
  for (int side = South; side <= West; ++side)
  {
    const bool horizontal = side == South || side == North;
    const std::size_t edge = static_cast<std::size_t>(horizontal
        ? edgeSampleCount(i0, i1, config.edgeLevel[side])
        : edgeSampleCount(j0, j1, config.edgeLevel[side]));
    const std::size_t inner = (horizontal ? nc : nr) - 2 + innerExtra[side];
    n += (edge - 1) + (inner - 1);
  }
  return n;
}

std::size_t mergedNodeTriangleCount(const Quadtree& qt, int node)
{
  const QuadtreeNode& n = qt.nodes[node];
  return 2 * static_cast<std::size_t>((n.colEnd - n.colBegin) + (n.rowEnd - n.rowBegin));
}

} // namespace gmm
