#include "Tessellate.h"

#include "CellDrawing.h"
#include "Levels.h"
#include "StripDrawing.h"
#include "TriangleSinks.h"

namespace gmm
{

namespace
{

struct BlockRect
{
  int i0, i1, j0, j1;
};

BlockRect blockRect(const Quadtree& qt, int block)
{
  const int c = block % qt.blockCols, r = block / qt.blockCols;
  return BlockRect{ qt.colStart[c], qt.colStart[c + 1], qt.rowStart[r], qt.rowStart[r + 1] };
}

// Whether `block` at `level` is drawn as cells (HoleCells.h): a block with nodata at a
// level above 0 (level 0 draws every sample anyway, with its four edges at full
// resolution: Quadtree::sideAtFullResolutionAt).
bool drawnAsHoleCells(const Quadtree& qt, int block, int level)
{
  return level > 0 && qt.blockHasNodata[block];
}

// Where the inner ring of a ring block at `level` runs along `side`: the second sample of
// the other axis from the side (edgeSamples at the level: the first step in from it, or,
// from the far side, the last sample before it, which a thin last interval moves in).
int innerRingAt(const BlockRect& r, int side, int level)
{
  switch (side)
  {
    case South:
      return r.j0 + (1 << level);
    case East:
      return r.i0 + (((r.i1 - r.i0 - 1) >> level) << level);
    case North:
      return r.j0 + (((r.j1 - r.j0 - 1) >> level) << level);
    default: // West
      return r.i0 + (1 << level);
  }
}

// The two polylines of one side strip (Tessellate.h, sidePolylines), in the block's
// counter-clockwise direction: the edge samples at the edge level (outer) and the inner
// ring's samples along that side (inner: `along`, the block's samples at its level along
// the side, at innerRingAt), or with `cells` (a block with nodata, whose border row along
// this side is clear of it), the cells' vertices along the row's inner line, and the
// strip's ends on the block's border (stripEnds).
void sideLines(const BlockRect& r, int level, const std::vector<int>& along, int innerAt, int side,
  int edgeLevel, EmitScratch& scratch, const HoleCells* cells)
{
  scratch.ring = RingGrid{ r.i0, r.j0, level, edgeSampleCount(r.i0, r.i1, level) - 1,
    edgeSampleCount(r.j0, r.j1, level) - 1 };
  std::vector<int>& edge = scratch.edge;
  std::vector<GridPoint>& outer = scratch.outer;
  std::vector<GridPoint>& inner = scratch.inner;
  outer.clear();
  inner.clear();
  const std::size_t n = along.size() - 1; // intervals along the side
  scratch.stripStart.clear();
  scratch.stripEnd.clear();
  if (cells)
  {
    innerRingLine(*cells, side, inner);
    stripEnds(*cells, side, scratch.stripStart, scratch.stripEnd);
  }
  switch (side)
  {
    case South:
      edgeSamples(r.i0, r.i1, edgeLevel, edge);
      for (int x : edge)
        outer.push_back({ x, r.j0 });
      for (std::size_t u = 1; !cells && u < n; ++u)
        inner.push_back({ along[u], innerAt });
      break;
    case East:
      edgeSamples(r.j0, r.j1, edgeLevel, edge);
      for (int y : edge)
        outer.push_back({ r.i1, y });
      for (std::size_t t = 1; !cells && t < n; ++t)
        inner.push_back({ innerAt, along[t] });
      break;
    case North:
      edgeSamples(r.i0, r.i1, edgeLevel, edge);
      for (auto it = edge.rbegin(); it != edge.rend(); ++it)
        outer.push_back({ *it, r.j1 });
      for (std::size_t u = n - 1; !cells && u >= 1; --u)
        inner.push_back({ along[u], innerAt });
      break;
    default: // West
      edgeSamples(r.j0, r.j1, edgeLevel, edge);
      for (auto it = edge.rbegin(); it != edge.rend(); ++it)
        outer.push_back({ r.i0, *it });
      for (std::size_t t = n - 1; !cells && t >= 1; --t)
        inner.push_back({ innerAt, along[t] });
      break;
  }
}

// The samples of a block at `level` along `side`'s axis (scratch.cols for south and north,
// rows for east and west), for a strip drawn without the rest of the block.
std::vector<int>& alongSide(const BlockRect& r, int side, int level, EmitScratch& scratch)
{
  const bool rows = side == South || side == North;
  std::vector<int>& along = rows ? scratch.cols : scratch.rows;
  if (rows)
  {
    edgeSamples(r.i0, r.i1, level, along);
  }
  else
  {
    edgeSamples(r.j0, r.j1, level, along);
  }
  return along;
}

BlockParts partsOf(BlockPart part)
{
  BlockParts parts;
  parts.inner = part == BlockPart::Whole || part == BlockPart::Inner;
  for (int side = South; side <= West; ++side)
  {
    parts.side[side] = part == BlockPart::Whole ||
      static_cast<int>(part) == static_cast<int>(BlockPart::StripSouth) + side;
  }
  return parts;
}

// A one-quad block: two triangles, or one fanned cell with a side at full resolution;
// their sides on glided edges cut at the finer block's samples (EdgeCutSink).
template <typename Sink>
void drawOneQuad(Sink& sink, const Quadtree& qt, int block, const BlockConfig& config, const BlockRect& r,
  EmitScratch& scratch)
{
  bool fine[4];
  if (oneQuadFineSides(qt, block, config, fine))
  {
    // A side at full resolution: the quad as one fanned cell (HoleCells.h).
    drawCellFan(sink, r.i0, r.j0, r.i1, r.j1, fine, scratch.inner, scratch.sides);
    return;
  }
  sink.quad(r.i0, r.j0, r.i1, r.j1, oneQuadAntiDiagonal(qt, block));
}

// The strip of `side` (sideLines, then drawSideLines), its triangles on a glided edge of a
// coarser block cut at the finer block's samples.
template <typename Sink>
void drawStrip(Sink& sink, const BlockConfig& config, const BlockRect& r, const std::vector<int>& along, int side,
  EmitScratch& scratch, const HoleCells* cells)
{
  sideLines(r, config.level, along, innerRingAt(r, side, config.level), side, config.stripEdgeLevel(side), scratch,
    cells);
  if (config.cutsSide(side))
  {
    EdgeCutSink<Sink> cut(sink, r.i0, r.i1, r.j0, r.j1, config);
    drawSideLines(cut, scratch, side);
    return;
  }
  drawSideLines(sink, scratch, side);
}

template <typename Sink>
void emitBlockTo(Sink& sink, const Quadtree& qt, int block, const BlockConfig& config,
  const BlockParts& parts, EmitScratch& scratch)
{
  const BlockRect r = blockRect(qt, block);
  const BlockShape shape = blockShape(r.i1 - r.i0, r.j1 - r.j0, config.level);
  if (shape == BlockShape::OneQuad || shape == BlockShape::Thin)
  {
    if (!parts.inner || !parts.everySide())
    {
      return;
    }
    if (shape == BlockShape::OneQuad)
    {
      if (config.cutsSide(South) || config.cutsSide(East) || config.cutsSide(North) || config.cutsSide(West))
      {
        EdgeCutSink<Sink> cut(sink, r.i0, r.i1, r.j0, r.j1, config);
        drawOneQuad(cut, qt, block, config, r, scratch);
        return;
      }
      drawOneQuad(sink, qt, block, config, r, scratch);
      return;
    }
    // Thin: the DEM is one quad wide or tall, so the long sides have no neighbours and the
    // short sides are single quads: a plain full-resolution strip is crack-free.
    for (int j = r.j0; j < r.j1; ++j)
      for (int i = r.i0; i < r.i1; ++i)
        sink.quad(i, j, i + 1, j + 1, fullResolutionAntiDiagonal(i, j));
    return;
  }
  if (shape != BlockShape::Ring)
  {
    return;
  }
  const HoleCells* cells = nullptr;
  if (drawnAsHoleCells(qt, block, config.level))
  {
    // Cells around the nodata (buildHoleCells finds the level's samples itself): over the
    // block, its border included, but for the border rows clear of nodata, which side
    // strips draw to the cells' vertices.
    buildHoleCells(qt, block, config.level, scratch.cells);
    if (parts.inner)
    {
      drawAreaAroundHoles(sink, scratch.cells, scratch.inner, scratch.sides);
    }
    if (!scratch.cells.anyStrip())
    {
      return;
    }
    cells = &scratch.cells;
  }
  // The block's samples at its level along each axis where a part reads them: the inner
  // grid both, a strip those along its side (a connect's strip across is drawn alone).
  // With cells the strips take their inner lines from the cells.
  std::vector<int>& C = scratch.cols;
  std::vector<int>& R = scratch.rows;
  if (!cells)
  {
    if (parts.inner || parts.side[South] || parts.side[North])
    {
      edgeSamples(r.i0, r.i1, config.level, C);
    }
    if (parts.inner || parts.side[East] || parts.side[West])
    {
      edgeSamples(r.j0, r.j1, config.level, R);
    }
    if (parts.inner)
    {
      drawInnerGrid(sink, C, R);
    }
  }
  for (int side = South; side <= West; ++side)
  {
    if (parts.side[side] && (!cells || cells->strip[side]))
    {
      drawStrip(sink, config, r, side == South || side == North ? C : R, side, scratch, cells);
    }
  }
}

template <typename Sink>
void emitBlockTo(Sink& sink, const Quadtree& qt, int block, const BlockConfig& config,
  BlockPart part, EmitScratch& scratch)
{
  emitBlockTo(sink, qt, block, config, partsOf(part), scratch);
}

// Drops the triangles over nodata of `block` unless told to keep them; where the block has
// no nodata there is nothing to drop, and the test would read each vertex's height.
TriangleSink blockSink(const Heightfield& hf, const Quadtree& qt, int block,
  std::vector<uint32_t>& out, bool keepNodata)
{
  return TriangleSink(hf, out, keepNodata || !qt.blockHasNodata[static_cast<std::size_t>(block)]);
}

} // namespace

void emitBlock(const Heightfield& hf, const Quadtree& qt, int block, const BlockConfig& config,
  BlockPart part, std::vector<uint32_t>& out, bool keepNodata)
{
  EmitScratch scratch;
  emitBlock(hf, qt, block, config, part, out, scratch, keepNodata);
}

void emitBlock(const Heightfield& hf, const Quadtree& qt, int block, const BlockConfig& config,
  BlockPart part, std::vector<uint32_t>& out, EmitScratch& scratch, bool keepNodata)
{
  // Every vertex is a sample of the block (borders included).
  TriangleSink sink = blockSink(hf, qt, block, out, keepNodata);
  emitBlockTo(sink, qt, block, config, part, scratch);
}

void emitBlockParts(const Heightfield& hf, const Quadtree& qt, int block, const BlockConfig& config,
  const BlockParts& parts, std::vector<uint32_t>& out, EmitScratch& scratch)
{
  TriangleSink sink = blockSink(hf, qt, block, out, false);
  emitBlockTo(sink, qt, block, config, parts, scratch);
}

void emitBlockGrid(const Quadtree& qt, int block, const BlockConfig& config, BlockPart part,
  std::vector<GridTriangle>& out, EmitScratch& scratch)
{
  GridSink sink(out);
  emitBlockTo(sink, qt, block, config, part, scratch);
}

void sidePolylines(const Quadtree& qt, int block, const BlockConfig& config, int side,
  EmitScratch& scratch, const HoleCells* cells)
{
  const BlockRect r = blockRect(qt, block);
  const std::vector<int>& along = alongSide(r, side, config.level, scratch);
  sideLines(r, config.level, along, innerRingAt(r, side, config.level), side, config.stripEdgeLevel(side), scratch,
    cells);
}

void emitHoleCellsGrid(const HoleCells& cells, std::vector<GridTriangle>& out, EmitScratch& scratch)
{
  GridSink sink(out);
  drawAreaAroundHoles(sink, cells, scratch.inner, scratch.sides);
}

void emitSidePolylinesGrid(const EmitScratch& lines, int side, std::vector<GridTriangle>& out)
{
  GridSink sink(out);
  drawSideLines(sink, lines, side);
}

bool oneQuadFineSides(const Quadtree& qt, int block, const BlockConfig& config, bool fine[4])
{
  bool any = false;
  for (int side = South; side <= West; ++side)
  {
    fine[side] = config.level > 0 && config.edgeLevel[side] == 0;
    any = any || fine[side];
  }
  return any && qt.blockWidth(block) >= 2 && qt.blockHeight(block) >= 2;
}

BlockConfig blockConfigOf(const Quadtree& qt, const std::vector<int8_t>& levels, int block)
{
  BlockConfig cfg;
  cfg.level = levels[block];
  const std::array<int, 4> neighbour = qt.blockNeighbours(block);
  for (int side = 0; side < 4; ++side)
  {
    cfg.edgeLevel[side] = edgeLevelOf(qt, levels, block, cfg.level, side, neighbour[side]);
    cfg.sampleLevel[side] = sampleLevelOf(qt, levels, block, cfg.level, neighbour[side], cfg.edgeLevel[side]);
  }
  return cfg;
}

LevelsAround levelsAround(const Quadtree& qt, const std::vector<int8_t>& levels, int block)
{
  const std::array<int, 4> neighbour = qt.blockNeighbours(block);
  LevelsAround around{ levels[block], kNoNeighbour, kNoNeighbour, kNoNeighbour, kNoNeighbour };
  for (int side = 0; side < 4; ++side)
  {
    if (neighbour[side] >= 0)
    {
      around[1 + side] = levels[neighbour[side]];
    }
  }
  return around;
}

} // namespace gmm
