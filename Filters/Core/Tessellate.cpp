#include "Tessellate.h"

#include "CellDrawing.h"
#include "Levels.h"
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

// One row band of the inner grid: quads between rows ja and jb over columns cols[0..count).
template <typename Sink>
void drawHStrip(Sink& sink, const int* cols, std::size_t count, int ja, int jb)
{
  for (std::size_t u = 0; u + 1 < count; ++u)
  {
    sink.quad(cols[u], ja, cols[u + 1], jb);
  }
}

// Inner grid of a ring block: samples cols[1..k-1] x rows[1..L-1] at the block's own step.
template <typename Sink>
void drawInnerGrid(Sink& sink, const std::vector<int>& C, const std::vector<int>& R)
{
  for (std::size_t t = 1; t + 2 < R.size(); ++t)
  {
    drawHStrip(sink, C.data() + 1, C.size() - 2, R[t], R[t + 1]);
  }
}

// Whether `block` at `level` is drawn as cells (HoleCells.h): a block with nodata at a
// level above 0 (level 0 draws every sample anyway, with its four edges at full
// resolution: Quadtree::sideAtFullResolutionAt).
bool drawnAsHoleCells(const Quadtree& qt, int block, int level)
{
  return level > 0 && qt.blockHasNodata[block];
}

// Fan from `apex` over consecutive points run[first..last], which lie on the line opposite
// the apex. apexOnOuter says which side of the strip the apex is on, to keep CCW order.
template <typename Sink>
void drawFan(Sink& sink, GridPoint apex, const std::vector<GridPoint>& run,
  std::size_t first, std::size_t last, bool apexOnOuter)
{
  for (std::size_t k = first; k < last; ++k)
  {
    if (apexOnOuter)
    {
      sink.triangle(apex, run[k + 1], run[k]); // (o_a, in_{b+1}, in_b)
    }
    else
    {
      sink.triangle(run[k], run[k + 1], apex); // (o_a, o_{a+1}, in_b)
    }
  }
}

// Joins the edge polyline (outer) to the inner ring polyline (inner[first..last]) of one
// side. Both run in the block's counter-clockwise direction; `along` gives each point's
// position along the side. The merge advances whichever polyline's next point comes first,
// which cuts the strip into alternating fans: any edge level joins any inner level. When
// the next outer and inner points are level (a regular quad, as when both sides have the
// block's level), `innerFirst` picks the quad's diagonal: the merge then splits it along
// the same (i, j)-(i+1, j+1) diagonal as the inner grid, so that a block with its own edges
// draws one regular triangulation (at level 0, exactly the full-resolution one).
template <typename Sink, typename Along>
void drawSideStrip(Sink& sink, const std::vector<GridPoint>& outer,
  const std::vector<GridPoint>& inner, std::size_t first, std::size_t last, Along along,
  bool innerFirst)
{
  // True when the outer point at position x is to be joined before the inner one at y.
  auto outerBefore = [innerFirst](int x, int y) { return innerFirst ? x < y : x <= y; };
  std::size_t a = 0, b = first;
  while (a + 1 < outer.size() || b < last)
  {
    const bool advanceOuter = b >= last ||
      (a + 1 < outer.size() && outerBefore(along(outer[a + 1]), along(inner[b + 1])));
    if (advanceOuter)
    {
      std::size_t end = a + 1;
      while (end + 1 < outer.size() && (b >= last || outerBefore(along(outer[end + 1]), along(inner[b + 1]))))
      {
        ++end;
      }
      drawFan(sink, inner[b], outer, a, end, false);
      a = end;
    }
    else
    {
      std::size_t end = b + 1;
      while (end < last && (a + 1 < outer.size() && !outerBefore(along(outer[a + 1]), along(inner[end + 1]))))
      {
        ++end;
      }
      if (a + 1 >= outer.size())
      {
        end = last;
      }
      drawFan(sink, outer[a], inner, b, end, true);
      b = end;
    }
  }
}

// The two polylines of one side strip (Tessellate.h, sidePolylines), in the block's
// counter-clockwise direction: the edge samples at the edge level (outer) and the inner
// ring's samples along that side (inner), or with `cells` (a block with nodata, whose
// border row along this side is clear of it), the cells' vertices along the row's inner
// line, and the strip's ends on the block's border (stripEnds).
void sideLines(const BlockRect& r, const std::vector<int>& C, const std::vector<int>& R, int side,
  int edgeLevel, EmitScratch& scratch, const HoleCells* cells)
{
  std::vector<int>& edge = scratch.edge;
  std::vector<GridPoint>& outer = scratch.outer;
  std::vector<GridPoint>& inner = scratch.inner;
  outer.clear();
  inner.clear();
  const std::size_t k = C.size() - 1, L = R.size() - 1;
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
      for (std::size_t u = 1; !cells && u < k; ++u)
        inner.push_back({ C[u], R[1] });
      break;
    case East:
      edgeSamples(r.j0, r.j1, edgeLevel, edge);
      for (int y : edge)
        outer.push_back({ r.i1, y });
      for (std::size_t t = 1; !cells && t < L; ++t)
        inner.push_back({ C[k - 1], R[t] });
      break;
    case North:
      edgeSamples(r.i0, r.i1, edgeLevel, edge);
      for (auto it = edge.rbegin(); it != edge.rend(); ++it)
        outer.push_back({ *it, r.j1 });
      for (std::size_t u = k - 1; !cells && u >= 1; --u)
        inner.push_back({ C[u], R[L - 1] });
      break;
    default: // West
      edgeSamples(r.j0, r.j1, edgeLevel, edge);
      for (auto it = edge.rbegin(); it != edge.rend(); ++it)
        outer.push_back({ r.i0, *it });
      for (std::size_t t = L - 1; !cells && t >= 1; --t)
        inner.push_back({ C[1], R[t] });
      break;
  }
}

// The strip of one side between its two polylines (sideLines), each side's direction
// along the border and diagonal choice. A strip that ends on the block's border (a block
// with nodata whose neighbouring side has no strip, HoleCells.h) first fans that end's
// border samples from the inner line's second (second-last) point, and joins the rest.
template <typename Sink>
void drawSideLines(Sink& sink, const EmitScratch& lines, int side)
{
  const std::vector<GridPoint>& outer = lines.outer;
  const std::vector<GridPoint>& inner = lines.inner;
  std::size_t first = 0, last = inner.size() - 1;
  if (!lines.stripStart.empty())
  {
    for (std::size_t k = 0; k + 1 < lines.stripStart.size(); ++k)
      triangleCCW(sink, inner[1], lines.stripStart[k], lines.stripStart[k + 1]);
    first = 1;
  }
  if (!lines.stripEnd.empty())
  {
    for (std::size_t k = 0; k + 1 < lines.stripEnd.size(); ++k)
      triangleCCW(sink, inner[last - 1], lines.stripEnd[k], lines.stripEnd[k + 1]);
    last -= 1;
  }
  switch (side)
  {
    case South:
      drawSideStrip(sink, outer, inner, first, last, [](GridPoint p) { return p.i; }, true);
      break;
    case East:
      drawSideStrip(sink, outer, inner, first, last, [](GridPoint p) { return p.j; }, false);
      break;
    case North:
      drawSideStrip(sink, outer, inner, first, last, [](GridPoint p) { return -p.i; }, true);
      break;
    default: // West
      drawSideStrip(sink, outer, inner, first, last, [](GridPoint p) { return -p.j; }, false);
      break;
  }
}

template <typename Sink>
void drawSide(Sink& sink, const BlockRect& r, const std::vector<int>& C,
  const std::vector<int>& R, int side, int edgeLevel, EmitScratch& scratch, const HoleCells* cells)
{
  sideLines(r, C, R, side, edgeLevel, scratch, cells);
  drawSideLines(sink, scratch, side);
}

// What of a block to draw: its inner part (the inner grid, or the cells of a block with
// nodata; a one-quad or thin block, which has no strips, only with every side) and which of
// its side strips.
struct PartsToDraw
{
  bool inner = false;
  std::array<bool, 4> side{ false, false, false, false };
  bool everySide() const { return side[0] && side[1] && side[2] && side[3]; }
};

PartsToDraw partsOf(BlockPart part)
{
  PartsToDraw parts;
  parts.inner = part == BlockPart::Whole || part == BlockPart::Inner;
  for (int side = South; side <= West; ++side)
  {
    parts.side[side] = part == BlockPart::Whole ||
      static_cast<int>(part) == static_cast<int>(BlockPart::StripSouth) + side;
  }
  return parts;
}

template <typename Sink>
void emitBlockTo(Sink& sink, const Quadtree& qt, int block, const BlockConfig& config,
  const PartsToDraw& parts, EmitScratch& scratch)
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
      bool fine[4];
      if (oneQuadFineSides(qt, block, config, fine))
      {
        // A side at full resolution: the quad as one fanned cell (HoleCells.h).
        drawCellFan(sink, r.i0, r.j0, r.i1, r.j1, fine, scratch.inner, scratch.sides);
        return;
      }
      if (oneQuadAntiDiagonal(qt, block))
      {
        // The quad split along its (i1, j0)-(i0, j1) diagonal.
        sink.triangle({ r.i0, r.j0 }, { r.i1, r.j0 }, { r.i0, r.j1 });
        sink.triangle({ r.i1, r.j0 }, { r.i1, r.j1 }, { r.i0, r.j1 });
      }
      else
      {
        sink.quad(r.i0, r.j0, r.i1, r.j1);
      }
      return;
    }
    // Thin: the DEM is one quad wide or tall, so the long sides have no neighbours and the
    // short sides are single quads: a plain full-resolution strip is crack-free.
    for (int j = r.j0; j < r.j1; ++j)
      for (int i = r.i0; i < r.i1; ++i)
        sink.quad(i, j, i + 1, j + 1);
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
  std::vector<int>& C = cells ? scratch.cells.cols : scratch.cols;
  std::vector<int>& R = cells ? scratch.cells.rows : scratch.rows;
  if (!cells)
  {
    edgeSamples(r.i0, r.i1, config.level, C);
    edgeSamples(r.j0, r.j1, config.level, R);
    if (parts.inner)
    {
      drawInnerGrid(sink, C, R);
    }
  }
  for (int side = South; side <= West; ++side)
  {
    if (parts.side[side] && (!cells || cells->strip[side]))
    {
      drawSide(sink, r, C, R, side, config.edgeLevel[side], scratch, cells);
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
  PartsToDraw strip;
  strip.side[side] = true;
  TriangleSink sink = blockSink(hf, qt, block, out, false);
  emitBlockTo(sink, qt, block, blockConfigOf(qt, levels, block), strip, scratch);
}

// The main area of a drawn block (the part of Poyart's drawArea before its connects): its
// inner grid (or cells, or its one quad), with the strips of its west and north sides where
// no connect joins them. At the DEM's border and beside culled space the edge is at the
// block's own level: the regular grid that Poyart's main area extends to.
void drawMainArea(const Heightfield& hf, const Quadtree& qt, const std::vector<int8_t>& levels,
  int block, const BlockConfig& config, const std::array<int, 4>& neighbour,
  std::vector<uint32_t>& out, EmitScratch& scratch)
{
  PartsToDraw parts;
  parts.inner = true;
  const BlockShape shape = blockShape(qt.blockWidth(block), qt.blockHeight(block), config.level);
  if (shape == BlockShape::Ring)
  {
    parts.side[West] = !sideDrawnByNeighbour(levels, neighbour[West]);
    parts.side[North] = !sideDrawnByNeighbour(levels, neighbour[North]);
  }
  else
  {
    parts.side = { true, true, true, true }; // no strips: all of it is area
  }
  TriangleSink sink = blockSink(hf, qt, block, out, false);
  emitBlockTo(sink, qt, block, config, parts, scratch);
}

// A connect across `side` (East or South) of `block`: the block's strip on that side, then,
// when a drawn block lies across it, that block's strip on the shared edge. Both strips end
// on the edge sampled at the coarser of the two levels (edgeLevelOf), which is what keeps
// each block's triangles, and so its error table, its own.
void drawConnect(const Heightfield& hf, const Quadtree& qt, const std::vector<int8_t>& levels,
  int block, const BlockConfig& config, int side, int neighbour, std::vector<uint32_t>& out,
  EmitScratch& scratch)
{
  PartsToDraw own;
  own.side[side] = true;
  TriangleSink sink = blockSink(hf, qt, block, out, false);
  emitBlockTo(sink, qt, block, config, own, scratch);
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
  edgeSamples(r.i0, r.i1, config.level, scratch.cols);
  edgeSamples(r.j0, r.j1, config.level, scratch.rows);
  sideLines(r, scratch.cols, scratch.rows, side, config.edgeLevel[side], scratch, cells);
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
