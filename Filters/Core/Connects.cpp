// Who draws what (Tessellate.h): Poyart's drawArea, each drawn block's main area and its
// east and south connects, and a merged node's fan with its connects; the keys the engine
// keeps slots by. The triangles themselves are emitBlock's and the merged fan's.
#include "Tessellate.h"

namespace gmm
{

namespace
{

// Whether the connect of what lies across the west or north side of a block draws that
// side's strip: a drawn block's or a merged node's does (drawEastConnect,
// drawSouthConnect); the DEM's border and culled space have none, and the strip is then
// the block's own.
bool sideDrawnByNeighbour(const std::vector<int8_t>& levels, int neighbour)
{
  return neighbour >= 0 && drawnLevel(levels[neighbour]);
}

// Whether a connect toward `neighbour` draws its strip on the shared edge: a drawn block
// has one; a merged node's fan has no strips (its perimeter is the edge).
bool hasStripAcross(const std::vector<int8_t>& levels, int neighbour)
{
  return neighbour >= 0 && levels[neighbour] >= 0;
}

// The strip of `block` (drawn at levels[block]) on `side`: a connect's half across.
void drawStripOf(const Heightfield& hf, const Quadtree& qt, const std::vector<int8_t>& levels,
  int block, int side, std::vector<uint32_t>& out, EmitScratch& scratch)
{
  BlockParts strip;
  strip.side[side] = true;
  emitBlockParts(hf, qt, block, blockConfigOf(qt, levels, block), strip, out, scratch);
}

// The main area of a drawn block (the part of Poyart's drawArea before its connects): its
// inner grid (or cells, or its one quad), with the strips of its west and north sides where
// no connect joins them. At the DEM's border and beside culled space the edge is at the
// block's own level: the regular grid that Poyart's main area extends to.
void drawMainArea(const Heightfield& hf, const Quadtree& qt, const std::vector<int8_t>& levels,
  int block, const BlockConfig& config, const std::array<int, 4>& neighbour,
  std::vector<uint32_t>& out, EmitScratch& scratch)
{
  BlockParts parts;
  parts.inner = true;
  if (qt.blockIsRingAt(block, config.level))
  {
    parts.side[West] = !sideDrawnByNeighbour(levels, neighbour[West]);
    parts.side[North] = !sideDrawnByNeighbour(levels, neighbour[North]);
  }
  else
  {
    parts.side = { true, true, true, true }; // no strips: all of it is area
  }
  emitBlockParts(hf, qt, block, config, parts, out, scratch);
}

// A connect across `side` (East or South) of `block`: the block's strip on that side, then,
// when a drawn block lies across it, that block's strip on the shared edge. Both strips end
// on the edge sampled at the coarser of the two levels (edgeLevelOf), which is what keeps
// each block's triangles, and so its error table, its own.
void drawConnect(const Heightfield& hf, const Quadtree& qt, const std::vector<int8_t>& levels,
  int block, const BlockConfig& config, int side, int neighbour, std::vector<uint32_t>& out,
  EmitScratch& scratch)
{
  BlockParts own;
  own.side[side] = true;
  emitBlockParts(hf, qt, block, config, own, out, scratch);
  if (hasStripAcross(levels, neighbour))
  {
    drawStripOf(hf, qt, levels, neighbour, (side + 2) % 4, out, scratch);
  }
}

// The blocks along the east (column colEnd) or south (row rowBegin - 1) side of a node,
// outside it, south to north / west to east; none at the DEM's border.
template <typename Visit>
void forEachBlockAlong(const Quadtree& qt, const QuadtreeNode& node, int side, Visit visit)
{
  if (side == East && node.colEnd < qt.blockCols)
  {
    for (int r = node.rowBegin; r < node.rowEnd; ++r)
      visit(qt.blockIndex(node.colEnd, r));
  }
  else if (side == South && node.rowBegin > 0)
  {
    for (int c = node.colBegin; c < node.colEnd; ++c)
      visit(qt.blockIndex(c, node.rowBegin - 1));
  }
}

void drawEastConnect(const Heightfield& hf, const Quadtree& qt, const std::vector<int8_t>& levels,
  int block, const BlockConfig& config, const std::array<int, 4>& neighbour,
  std::vector<uint32_t>& out, EmitScratch& scratch)
{
  drawConnect(hf, qt, levels, block, config, East, neighbour[East], out, scratch);
}

void drawSouthConnect(const Heightfield& hf, const Quadtree& qt, const std::vector<int8_t>& levels,
  int block, const BlockConfig& config, const std::array<int, 4>& neighbour,
  std::vector<uint32_t>& out, EmitScratch& scratch)
{
  drawConnect(hf, qt, levels, block, config, South, neighbour[South], out, scratch);
}

} // namespace

void drawArea(const Heightfield& hf, const Quadtree& qt, const std::vector<int8_t>& levels,
  int block, const BlockConfig& config, std::vector<uint32_t>& out, EmitScratch& scratch)
{
  const std::array<int, 4> neighbour = qt.blockNeighbours(block);
  drawMainArea(hf, qt, levels, block, config, neighbour, out, scratch);
  drawEastConnect(hf, qt, levels, block, config, neighbour, out, scratch);
  drawSouthConnect(hf, qt, levels, block, config, neighbour, out, scratch);
}

DrawnSides drawnSidesOf(const Quadtree& qt, const std::vector<int8_t>& levels, int block,
  const BlockConfig& config)
{
  DrawnSides key;
  key.config = config;
  const std::array<int, 4> neighbour = qt.blockNeighbours(block);
  for (int side : { West, North })
  {
    if (qt.blockIsRingAt(block, config.level) && sideDrawnByNeighbour(levels, neighbour[side]))
    {
      key.config.edgeLevel[side] = -1; // that strip is the neighbour's to draw
    }
  }
  for (int side : { East, South })
  {
    const int nb = neighbour[side];
    if (hasStripAcross(levels, nb))
    {
      const int opposite = (side + 2) % 4;
      key.across[side == East ? 0 : 1] = { levels[nb],
        static_cast<int8_t>(edgeLevelOf(qt, levels, nb, levels[nb], opposite, block)) };
    }
  }
  return key;
}

void drawMergedArea(const Heightfield& hf, const Quadtree& qt, const std::vector<int8_t>& levels,
  int node, std::vector<uint32_t>& out, EmitScratch& scratch)
{
  emitMergedNode(hf, qt, node, out, scratch);
  for (int side : { East, South })
  {
    forEachBlockAlong(qt, qt.nodes[node], side, [&](int b) {
      if (hasStripAcross(levels, b))
      {
        drawStripOf(hf, qt, levels, b, (side + 2) % 4, out, scratch);
      }
    });
  }
}

void tessellate(const Heightfield& hf, const Quadtree& qt, const std::vector<int8_t>& levels,
  std::vector<uint32_t>& out, const std::vector<int>& merged)
{
  out.clear();
  EmitScratch scratch;
  for (int b = 0; b < qt.blockCount(); ++b)
  {
    if (levels[b] >= 0)
    {
      drawArea(hf, qt, levels, b, blockConfigOf(qt, levels, b), out, scratch);
    }
  }
  for (int n : merged)
  {
    drawMergedArea(hf, qt, levels, n, out, scratch);
  }
}

} // namespace gmm
