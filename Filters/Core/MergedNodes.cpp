// Merged nodes (Tessellate.h): a quadtree node drawn whole as one fan.
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
  for (int c = n.colBegin; c < n.colEnd; ++c)
    out.push_back({ qt.colStart[c], j0 }); // south, west to east
  for (int r = n.rowBegin; r < n.rowEnd; ++r)
    out.push_back({ i1, qt.rowStart[r] }); // east, south to north
  for (int c = n.colEnd; c > n.colBegin; --c)
    out.push_back({ qt.colStart[c], j1 }); // north, east to west
  for (int r = n.rowEnd; r > n.rowBegin; --r)
    out.push_back({ i0, qt.rowStart[r] }); // west, north to south
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
