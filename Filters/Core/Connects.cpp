// Who draws what (Tessellate.h): Poyart's drawArea, each drawn block's main area and its
// east and south connects, and a merged node's fan with its connects; the keys the engine
// keeps slots by. The triangles themselves are emitBlock's and the merged fan's.
#include "Tessellate.h"

#include <algorithm>

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

// Whether a connect toward `neighbour` draws its strip on the shared edge: a block drawn
// as a ring has one; a block drawn as its one quad (or thin) has none (its area reaches its
// border), nor has a merged node's fan (its perimeter is the edge).
bool hasStripAcross(const Quadtree& qt, const std::vector<int8_t>& levels, int neighbour)
{
  return neighbour >= 0 && levels[neighbour] >= 0 && qt.blockIsRingAt(neighbour, levels[neighbour]);
}

// The strip of `block` on `side`, the block drawn at `level` and that side's edge at
// `edgeLevel` and `sampleLevel` (BlockConfig): a connect's half across. A strip reads no other part of its block's
// configuration (emitBlockParts), so the caller passes what it already knows.
void drawStripOf(const Heightfield& hf, const Quadtree& qt, int block, int level, int side,
  int edgeLevel, int sampleLevel, std::vector<uint32_t>& out, EmitScratch& scratch)
{
  BlockConfig config;
  config.level = level;
  config.edgeLevel.fill(level);
  config.edgeLevel[side] = edgeLevel;
  config.sampleLevel[side] = sampleLevel;
  BlockParts strip;
  strip.side[side] = true;
  emitBlockParts(hf, qt, block, config, strip, out, scratch);
}

// The parts of a drawn block's main area (Poyart's drawArea before its connects): its inner
// grid (or cells, or its one quad), with the strips of its west and north sides where no
// connect joins them (its key keeps their edge levels: drawnSidesOf). At the DEM's border
// and beside culled space the edge is at the block's own level: the regular grid that
// Poyart's main area extends to. A block without strips has every side in its area.
BlockParts mainAreaParts(const DrawnSides& key)
{
  BlockParts parts;
  parts.inner = true;
  parts.side[West] = key.config.edgeLevel[West] >= 0;
  parts.side[North] = key.config.edgeLevel[North] >= 0;
  return parts;
}

// A connect across `side` (East or South) of a block is the block's strip on that side and,
// when a drawn block lies across it, that block's strip on the shared edge. Both strips end
// on the edge sampled at the coarser of the two levels (edgeLevelOf), which is what keeps
// each block's triangles, and so its error table, its own. The block's own strip is emitted
// with its main area, in one pass over the block (drawArea); these draw the strip across,
// with the level and edge level the block's key holds for it.
void drawConnectAcross(const Heightfield& hf, const Quadtree& qt, const DrawnSides& key, int side,
  int neighbour, std::vector<uint32_t>& out, EmitScratch& scratch)
{
  const std::array<int8_t, 3>& across = key.across[side == East ? 0 : 1];
  if (across[0] >= 0)
  {
    drawStripOf(hf, qt, neighbour, across[0], (side + 2) % 4, across[1], across[2], out, scratch);
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

void drawEastConnect(const Heightfield& hf, const Quadtree& qt, const DrawnSides& key,
  const std::array<int, 4>& neighbour, std::vector<uint32_t>& out, EmitScratch& scratch)
{
  drawConnectAcross(hf, qt, key, East, neighbour[East], out, scratch);
}

void drawSouthConnect(const Heightfield& hf, const Quadtree& qt, const DrawnSides& key,
  const std::array<int, 4>& neighbour, std::vector<uint32_t>& out, EmitScratch& scratch)
{
  drawConnectAcross(hf, qt, key, South, neighbour[South], out, scratch);
}

} // namespace

void drawArea(const Heightfield& hf, const Quadtree& qt, int block, const DrawnSides& key,
  std::vector<uint32_t>& out, EmitScratch& scratch)
{
  // The block's own triangles in one pass (its rows and columns sampled once): its main
  // area and its strips of the east and south connects. Then the connects' strips across.
  BlockParts own = mainAreaParts(key);
  own.side[East] = own.side[South] = true;
  emitBlockParts(hf, qt, block, key.config, own, out, scratch);
  const std::array<int, 4> neighbour = qt.blockNeighbours(block);
  drawEastConnect(hf, qt, key, neighbour, out, scratch);
  drawSouthConnect(hf, qt, key, neighbour, out, scratch);
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
      key.config.sampleLevel[side] = -1;
    }
  }
  for (int side : { East, South })
  {
    const int nb = neighbour[side];
    if (hasStripAcross(qt, levels, nb))
    {
      // The edge and sample levels are the block's own on that side: both blocks of an edge
      // answer edgeLevelOf and sampleLevelOf alike when both are drawn as blocks.
      key.across[side == East ? 0 : 1] = { levels[nb], static_cast<int8_t>(config.edgeLevel[side]),
        static_cast<int8_t>(config.sampleLevel[side]) };
    }
  }
  return key;
}

void drawMergedArea(const Heightfield& hf, const Quadtree& qt, const std::vector<int8_t>& levels,
  int node, std::vector<uint32_t>& out, EmitScratch& scratch, const std::vector<int8_t>* nodeDepth)
{
  if (nodeDepth)
  {
    const PerimeterContext across{ levels, *nodeDepth };
    emitMergedNode(hf, qt, node, out, scratch, &across);
  }
  else
  {
    emitMergedNode(hf, qt, node, out, scratch);
  }
  for (int side : { East, South })
  {
    forEachBlockAlong(qt, qt.nodes[node], side, [&](int b) {
      if (hasStripAcross(qt, levels, b))
      {
        // Beside a merged node the edge is the block's corners (edgeLevelOf), never glided.
        const int opposite = (side + 2) % 4;
        drawStripOf(hf, qt, b, levels[b], opposite,
          edgeLevelOf(qt, levels, b, levels[b], opposite, qt.blockNeighbours(b)[opposite]), -1, out, scratch);
      }
    });
  }
}

void tessellate(const Heightfield& hf, const Quadtree& qt, const std::vector<int8_t>& levels,
  std::vector<uint32_t>& out, const std::vector<int>& merged, const std::vector<int8_t>* mergedDepth)
{
  out.clear();
  EmitScratch scratch;
  for (int b = 0; b < qt.blockCount(); ++b)
  {
    if (levels[b] >= 0)
    {
      drawArea(hf, qt, b, drawnSidesOf(qt, levels, b, blockConfigOf(qt, levels, b)), out, scratch);
    }
  }
  // In node order, as the engine's slots come (Engine::indices), whatever the list's order.
  std::vector<int> nodes(merged);
  std::sort(nodes.begin(), nodes.end());
  std::vector<int8_t> depth;
  if (mergedDepth)
  {
    depth.assign(qt.nodes.size(), -1);
    for (std::size_t k = 0; k < merged.size(); ++k)
    {
      depth[merged[k]] = (*mergedDepth)[k];
    }
  }
  for (int n : nodes)
  {
    drawMergedArea(hf, qt, levels, n, out, scratch, mergedDepth ? &depth : nullptr);
  }
}

} // namespace gmm
