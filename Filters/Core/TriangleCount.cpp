#include "TriangleCount.h"

#include "HoleCells.h"
#include "Levels.h"

#include <vector>

namespace gmm
{

std::size_t blockTriangleCount(
  const Quadtree& qt, int block, const BlockConfig& config, const ErrorTable* table)
{
  const int c = block % qt.blockCols, r = block / qt.blockCols;
  const int i0 = qt.colStart[c], i1 = qt.colStart[c + 1];
  const int j0 = qt.rowStart[r], j1 = qt.rowStart[r + 1];
  const int w = i1 - i0, h = j1 - j0;
  switch (blockShape(w, h, config.level))
  {
    case BlockShape::OneQuad:
    {
      bool fine[4];
      std::size_t n = oneQuadFineSides(qt, block, config, fine) ? fannedCellTriangleCount(w, h, fine) : 2;
      // Each sample of a glided edge between the corners cuts one triangle in two.
      for (int side = South; side <= West; ++side)
      {
        if (config.cutsSide(side))
        {
          const bool horizontal = side == South || side == North;
          n += static_cast<std::size_t>(horizontal ? edgeSampleCount(i0, i1, config.sampleLevel[side])
                                                   : edgeSampleCount(j0, j1, config.sampleLevel[side])) - 2;
        }
      }
      return n;
    }
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
  // Side strips' fans emit one triangle per step along either polyline; this is the edge's
  // (at its drawn samples: a glided edge's cuts add one triangle a sample).
  auto edgeSteps = [&](int side) {
    const bool horizontal = side == South || side == North;
    return static_cast<std::size_t>(horizontal ? edgeSampleCount(i0, i1, config.drawnEdgeLevel(side))
                                               : edgeSampleCount(j0, j1, config.drawnEdgeLevel(side))) - 1;
  };
  if (config.level == 0 && qt.blockHasNodata[block])
  {
    // Every quad (its sides are all at full resolution: Quadtree::followsEdgeLevels), less
    // the triangles that nodata drops.
    return table && !table->cellTriangles.empty()
      ? table->cellTriangles[static_cast<std::size_t>(block) * table->levels]
      : drawnTriangleCount(qt, block, config);
  }
  if (config.level > 0 && qt.blockHasNodata[block])
  {
    // Cells over the block but for the border rows clear of nodata, which side strips draw
    // (HoleCells.h): the cells and the strips' steps along their inner lines are a count of
    // the level alone, the steps along their edges follow the configuration.
    std::size_t n = 0;
    if (table && !table->cellTriangles.empty())
    {
      n = table->cellTriangles[static_cast<std::size_t>(block) * table->levels + config.level];
    }
    else
    {
      HoleCells cells;
      buildHoleCells(qt, block, config.level, cells);
      n = holeCellsTriangleCount(cells);
    }
    for (int side = South; side <= West; ++side)
    {
      n += qt.sideClearOfNodata(block, side, config.level) ? edgeSteps(side) : 0;
    }
    return n;
  }
  std::size_t n = 2 * (nc - 3) * (nr - 3);
  for (int side = South; side <= West; ++side)
  {
    const bool horizontal = side == South || side == North;
    const std::size_t inner = (horizontal ? nc : nr) - 2;
    n += edgeSteps(side) + (inner - 1);
  }
  return n;
}

std::size_t drawnTriangleCount(const Quadtree& qt, int block, const BlockConfig& config)
{
  if (qt.everySampleNodata(block))
  {
    return 0; // every vertex is nodata (the sea of a coastal tile: most of N48W125's blocks)
  }
  std::vector<GridTriangle> triangles;
  EmitScratch scratch;
  emitBlockGrid(qt, block, config, BlockPart::Whole, triangles, scratch);
  std::size_t n = 0;
  for (const GridTriangle& t : triangles)
  {
    bool valid = true;
    for (const GridPoint& p : t.v)
    {
      valid = valid && !qt.sampleIsNodata(block, p.i, p.j);
    }
    n += valid ? 1 : 0;
  }
  return n;
}

std::size_t mergedNodeTriangleCount(const Quadtree& qt, int node)
{
  // One triangle per perimeter sample (mergedPerimeter): each border block's side adds its
  // far corner, or every sample along it at full resolution.
  const QuadtreeNode& n = qt.nodes[node];
  std::size_t count = 0;
  for (int c = n.colBegin; c < n.colEnd; ++c)
  {
    const std::size_t w = static_cast<std::size_t>(qt.colStart[c + 1] - qt.colStart[c]);
    count += qt.sideAtFullResolution(qt.blockIndex(c, n.rowBegin), South) ? w : 1;
    count += qt.sideAtFullResolution(qt.blockIndex(c, n.rowEnd - 1), North) ? w : 1;
  }
  for (int r = n.rowBegin; r < n.rowEnd; ++r)
  {
    const std::size_t h = static_cast<std::size_t>(qt.rowStart[r + 1] - qt.rowStart[r]);
    count += qt.sideAtFullResolution(qt.blockIndex(n.colBegin, r), West) ? h : 1;
    count += qt.sideAtFullResolution(qt.blockIndex(n.colEnd - 1, r), East) ? h : 1;
  }
  return count;
}

std::size_t fullResolutionTrianglesInView(const Quadtree& qt, const Frustum& frustum)
{
  std::size_t total = 0;
  if (!qt.nodes.empty())
  {
    forNodesInFrustum(qt, 0, frustum, [&](int node) {
      const QuadtreeNode& n = qt.nodes[node];
      total += 2 * static_cast<std::size_t>(qt.colStart[n.colEnd] - qt.colStart[n.colBegin]) *
        static_cast<std::size_t>(qt.rowStart[n.rowEnd] - qt.rowStart[n.rowBegin]);
    });
  }
  return total;
}

} // namespace gmm
