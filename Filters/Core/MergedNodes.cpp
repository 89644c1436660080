// Merged nodes (Tessellate.h): a quadtree node drawn whole as one fan.
#include "Levels.h"
#include "Tessellate.h"
#include "TriangleSinks.h"

namespace gmm
{

bool mergeableNode(const Quadtree& qt, int node)
{
  // At least 2 x 2 blocks: the fan then has no more triangles than its blocks at their
  // coarsest (2 (c + r) <= 2 c r), and its centre sample is strictly inside.
  const QuadtreeNode& n = qt.nodes[node];
  return n.colEnd - n.colBegin >= 2 && n.rowEnd - n.rowBegin >= 2;
}

bool mergeNestsInBlocks(const Quadtree& qt, int node)
{
  const QuadtreeNode& n = qt.nodes[node];
  if (n.colEnd - n.colBegin != 2 || n.rowEnd - n.rowBegin != 2)
  {
    return false;
  }
  for (int r = n.rowBegin; r < n.rowEnd; ++r)
  {
    for (int c = n.colBegin; c < n.colEnd; ++c)
    {
      const int b = qt.blockIndex(c, r);
      const int w = qt.blockWidth(b), h = qt.blockHeight(b);
      if (blockShape(w, h, qt.blockTopLevel(b)) != BlockShape::OneQuad || qt.anySideAtFullResolution(b))
      {
        return false;
      }
    }
  }
  return true;
}

GridPoint mergedCentre(const Quadtree& qt, int node)
{
  // Where the quadtree splits the node's block columns and rows: a block corner strictly
  // inside a mergeable node.
  const QuadtreeNode& n = qt.nodes[node];
  return GridPoint{ qt.colStart[splitBand(n.colBegin, n.colEnd)], qt.rowStart[splitBand(n.rowBegin, n.rowEnd)] };
}

void mergedPerimeter(const Quadtree& qt, int node, std::vector<GridPoint>& out)
{
  out.clear();
  const QuadtreeNode& n = qt.nodes[node];
  const int i0 = qt.colStart[n.colBegin], i1 = qt.colStart[n.colEnd];
  const int j0 = qt.rowStart[n.rowBegin], j1 = qt.rowStart[n.rowEnd];
  // From each block corner along one border block's side: the next corner, or every sample
  // when that side is at full resolution (a block with nodata across it).
  for (int c = n.colBegin; c < n.colEnd; ++c) // south, west to east
  {
    const bool fine = qt.sideAtFullResolution(qt.blockIndex(c, n.rowBegin), South);
    for (int i = qt.colStart[c]; i < qt.colStart[c + 1]; i = fine ? i + 1 : qt.colStart[c + 1])
      out.push_back({ i, j0 });
  }
  for (int r = n.rowBegin; r < n.rowEnd; ++r) // east, south to north
  {
    const bool fine = qt.sideAtFullResolution(qt.blockIndex(n.colEnd - 1, r), East);
    for (int j = qt.rowStart[r]; j < qt.rowStart[r + 1]; j = fine ? j + 1 : qt.rowStart[r + 1])
      out.push_back({ i1, j });
  }
  for (int c = n.colEnd; c > n.colBegin; --c) // north, east to west
  {
    const bool fine = qt.sideAtFullResolution(qt.blockIndex(c - 1, n.rowEnd - 1), North);
    for (int i = qt.colStart[c]; i > qt.colStart[c - 1]; i = fine ? i - 1 : qt.colStart[c - 1])
      out.push_back({ i, j1 });
  }
  for (int r = n.rowEnd; r > n.rowBegin; --r) // west, north to south
  {
    const bool fine = qt.sideAtFullResolution(qt.blockIndex(n.colBegin, r - 1), West);
    for (int j = qt.rowStart[r]; j > qt.rowStart[r - 1]; j = fine ? j - 1 : qt.rowStart[r - 1])
      out.push_back({ i0, j });
  }
}

namespace
{
template <typename Sink>
void emitMergedTo(Sink& sink, const Quadtree& qt, int node, std::vector<GridPoint>& perimeter)
{
  if (!mergeableNode(qt, node))
  {
    return;
  }
  mergedPerimeter(qt, node, perimeter);
  const GridPoint centre = mergedCentre(qt, node);
  for (std::size_t k = 0; k < perimeter.size(); ++k)
  {
    sink.triangle(centre, perimeter[k], perimeter[(k + 1) % perimeter.size()]);
  }
}
} // namespace

void emitMergedNode(const Heightfield& hf, const Quadtree& qt, int node, std::vector<uint32_t>& out)
{
  EmitScratch scratch;
  emitMergedNode(hf, qt, node, out, scratch);
}

void emitMergedNode(const Heightfield& hf, const Quadtree& qt, int node, std::vector<uint32_t>& out,
  EmitScratch& scratch)
{
  TriangleSink sink(hf, out, false);
  emitMergedTo(sink, qt, node, scratch.outer);
}

void emitMergedNodeGrid(const Quadtree& qt, int node, std::vector<GridTriangle>& out)
{
  GridSink sink(out);
  std::vector<GridPoint> perimeter;
  emitMergedTo(sink, qt, node, perimeter);
}

} // namespace gmm
