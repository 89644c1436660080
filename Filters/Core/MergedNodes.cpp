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

bool partitionBoundary(int b0, int b1, int depth, int c)
{
  for (;; --depth)
  {
    if (c == b0 || c == b1)
    {
      return true;
    }
    if (depth <= 0 || c < b0 || c > b1)
    {
      return false;
    }
    const int m = splitBand(b0, b1);
    if (c == m)
    {
      return true;
    }
    (c < m ? b1 : b0) = m;
  }
}

namespace
{
// The points a node's perimeter passes through along one side: its band boundaries
// (`cols`: block columns, else rows), the elements across it in block row or column
// `across` (-1 or past the DEM: none). Decides, for a boundary strictly inside the side,
// whether the node's own partition or a drawn element across needs it.
class SidePoints
{
public:
  SidePoints(const Quadtree& qt, const QuadtreeNode& n, int depth, const PerimeterContext* ctx, bool cols,
    int across)
    : qt_(qt)
    , n_(n)
    , depth_(depth)
    , ctx_(ctx)
    , cols_(cols)
    , across_(across)
  {
  }

  bool wanted(int c)
  {
    const int b0 = cols_ ? n_.colBegin : n_.rowBegin, b1 = cols_ ? n_.colEnd : n_.rowEnd;
    return partitionBoundary(b0, b1, depth_, c) || (ctx_ && (wantedAcross(c - 1, c) || wantedAcross(c, c)));
  }

private:
  // Whether the element drawn across band `band` of the line has a point at boundary c.
  bool wantedAcross(int band, int c)
  {
    const int acrossBands = cols_ ? qt_.blockRows : qt_.blockCols;
    if (across_ < 0 || across_ >= acrossBands)
    {
      return false; // the DEM's border
    }
    const int col = cols_ ? band : across_, row = cols_ ? across_ : band;
    const int level = ctx_->levels[qt_.blockIndex(col, row)];
    if (level >= 0)
    {
      return true; // a block drawn by itself: its corners
    }
    if (level != kCoveredLevel)
    {
      return false; // not drawn: nothing across to meet
    }
    const QuadtreeNode* b = coveringNode(col, row);
    if (!b)
    {
      return true;
    }
    const int d = ctx_->depth[b - qt_.nodes.data()];
    return d >= b->height || partitionBoundary(cols_ ? b->colBegin : b->rowBegin, cols_ ? b->colEnd : b->rowEnd, d, c);
  }

  // The node drawn whole now over block (col, row), down from the root (the last one found
  // first: along a side, neighbours come in runs); null if none.
  const QuadtreeNode* coveringNode(int col, int row)
  {
    auto holds = [&](const QuadtreeNode& m) {
      return col >= m.colBegin && col < m.colEnd && row >= m.rowBegin && row < m.rowEnd;
    };
    if (last_ && holds(*last_))
    {
      return last_;
    }
    const int at = qt_.firstNodeOver(col, row, [this](int n) { return ctx_->depth[n] >= 0; });
    if (at < 0)
    {
      return nullptr;
    }
    last_ = &qt_.nodes[at];
    return last_;
  }

  const Quadtree& qt_;
  const QuadtreeNode& n_;
  int depth_;
  const PerimeterContext* ctx_;
  bool cols_;
  int across_;
  const QuadtreeNode* last_ = nullptr;
};
} // namespace

void coarsePerimeter(const Quadtree& qt, int node, int depth, const PerimeterContext* across,
  std::vector<GridPoint>& out)
{
  out.clear();
  const QuadtreeNode& n = qt.nodes[node];
  const int i0 = qt.colStart[n.colBegin], i1 = qt.colStart[n.colEnd];
  const int j0 = qt.rowStart[n.rowBegin], j1 = qt.rowStart[n.rowEnd];
  SidePoints south(qt, n, depth, across, true, n.rowBegin - 1);
  for (int c = n.colBegin; c < n.colEnd; ++c) // west to east
    if (c == n.colBegin || south.wanted(c))
      out.push_back({ qt.colStart[c], j0 });
  SidePoints east(qt, n, depth, across, false, n.colEnd);
  for (int r = n.rowBegin; r < n.rowEnd; ++r) // south to north
    if (r == n.rowBegin || east.wanted(r))
      out.push_back({ i1, qt.rowStart[r] });
  SidePoints north(qt, n, depth, across, true, n.rowEnd);
  for (int c = n.colEnd; c > n.colBegin; --c) // east to west
    if (c == n.colEnd || north.wanted(c))
      out.push_back({ qt.colStart[c], j1 });
  SidePoints west(qt, n, depth, across, false, n.colBegin - 1);
  for (int r = n.rowEnd; r > n.rowBegin; --r) // north to south
    if (r == n.rowEnd || west.wanted(r))
      out.push_back({ i0, qt.rowStart[r] });
}

namespace
{
// The fan at perimeter depth `depth` (>= the node's height: every block corner).
template <typename Sink>
void emitMergedTo(Sink& sink, const Quadtree& qt, int node, std::vector<GridPoint>& perimeter, int depth,
  const PerimeterContext* across)
{
  if (!mergeableNode(qt, node))
  {
    return;
  }
  if (depth < qt.nodes[node].height)
  {
    coarsePerimeter(qt, node, depth, across, perimeter);
  }
  else
  {
    mergedPerimeter(qt, node, perimeter);
  }
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
  EmitScratch& scratch, const PerimeterContext* across)
{
  TriangleSink sink(hf, out, false);
  const int depth = across ? across->depth[node] : qt.nodes[node].height;
  emitMergedTo(sink, qt, node, scratch.outer, depth < 0 ? qt.nodes[node].height : depth, across);
}

void emitMergedNodeGrid(const Quadtree& qt, int node, std::vector<GridTriangle>& out)
{
  GridSink sink(out);
  std::vector<GridPoint> perimeter;
  emitMergedTo(sink, qt, node, perimeter, qt.nodes[node].height, nullptr);
}

} // namespace gmm
