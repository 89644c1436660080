#include "Tessellate.h"

#include "Levels.h"
#include "TriangleSinks.h"

#include <algorithm>

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
void drawArea(Sink& sink, const std::vector<int>& C, const std::vector<int>& R)
{
  for (std::size_t t = 1; t + 2 < R.size(); ++t)
  {
    drawHStrip(sink, C.data() + 1, C.size() - 2, R[t], R[t + 1]);
  }
}

// Emits triangle (a, b, c) counter-clockwise in (i, j), whichever order it is given in.
template <typename Sink>
void triangleCCW(Sink& sink, GridPoint a, GridPoint b, GridPoint c)
{
  const long long cross = static_cast<long long>(b.i - a.i) * (c.j - a.j) -
    static_cast<long long>(b.j - a.j) * (c.i - a.i);
  if (cross > 0)
    sink.triangle(a, b, c);
  else
    sink.triangle(a, c, b);
}

// The quad between two opposite sides that both have points between their corners:
// `lower` and `upper` run along them in the same direction, `first` is the side that joins
// lower[0] to upper[0] and `last` the one that joins their last points (each from the
// lower side's corner to the upper side's, corners included). A side between them with
// points inside is fanned from the lower (first) or upper (last) side's nearest inner
// point; the rest is a strip that zigzags between the two sides. Every triangle has two
// points on one line and one on another, so none is degenerate, and there are two fewer
// than points (a fan from the centre would draw two more).
template <typename Sink, typename Along>
void drawBetweenSides(Sink& sink, const std::vector<GridPoint>& lower,
  const std::vector<GridPoint>& upper, const std::vector<GridPoint>& first,
  const std::vector<GridPoint>& last, Along along)
{
  std::size_t a = 0, b = 0, aEnd = lower.size() - 1, bEnd = upper.size() - 1;
  if (first.size() > 2)
  {
    for (std::size_t k = 0; k + 1 < first.size(); ++k)
      triangleCCW(sink, lower[1], first[k], first[k + 1]);
    a = 1;
  }
  if (last.size() > 2)
  {
    for (std::size_t k = 0; k + 1 < last.size(); ++k)
      triangleCCW(sink, upper[bEnd - 1], last[k], last[k + 1]);
    --bEnd;
  }
  while (a < aEnd || b < bEnd)
  {
    if (b == bEnd || (a < aEnd && along(lower[a + 1]) <= along(upper[b + 1])))
    {
      triangleCCW(sink, lower[a], lower[a + 1], upper[b]);
      ++a;
    }
    else
    {
      triangleCCW(sink, lower[a], upper[b + 1], upper[b]);
      ++b;
    }
  }
}

// The quad [i0, i1] x [j0, j1] over its perimeter (counter-clockwise from its south-west
// corner, each corner once), `fine` saying which sides have points between their corners,
// in two fewer triangles than points: a fan from a corner between two sides without
// (HoleCells.h, coarseCorner), else (two opposite sides have points) drawBetweenSides.
template <typename Sink>
void drawCellPerimeter(Sink& sink, int i0, int j0, int i1, int j1, const bool fine[4],
  const std::vector<GridPoint>& perimeter, EmitSides& sides)
{
  const int corner = coarseCorner(fine);
  if (corner >= 0)
  {
    // From that corner: every other perimeter point lies on a side away from it.
    const GridPoint apex = corner == 0 ? GridPoint{ i0, j0 } : corner == 1 ? GridPoint{ i1, j0 }
      : corner == 2 ? GridPoint{ i1, j1 } : GridPoint{ i0, j1 };
    std::size_t at = 0;
    while (perimeter[at].i != apex.i || perimeter[at].j != apex.j)
      ++at;
    const std::size_t n = perimeter.size();
    for (std::size_t k = 1; k + 1 < n; ++k)
    {
      sink.triangle(apex, perimeter[(at + k) % n], perimeter[(at + k + 1) % n]);
    }
    return;
  }
  // Each side's points, in increasing i (South, North) or j (West, East), corners included.
  for (auto& side : sides.points)
    side.clear();
  for (const GridPoint& p : perimeter)
  {
    if (p.j == j0)
      sides.points[South].push_back(p);
    if (p.j == j1)
      sides.points[North].push_back(p);
    if (p.i == i0)
      sides.points[West].push_back(p);
    if (p.i == i1)
      sides.points[East].push_back(p);
  }
  auto byI = [](GridPoint p, GridPoint q) { return p.i < q.i; };
  auto byJ = [](GridPoint p, GridPoint q) { return p.j < q.j; };
  std::sort(sides.points[South].begin(), sides.points[South].end(), byI);
  std::sort(sides.points[North].begin(), sides.points[North].end(), byI);
  std::sort(sides.points[West].begin(), sides.points[West].end(), byJ);
  std::sort(sides.points[East].begin(), sides.points[East].end(), byJ);
  if (fine[South] && fine[North])
  {
    drawBetweenSides(sink, sides.points[South], sides.points[North], sides.points[West],
      sides.points[East], [](GridPoint p) { return p.i; });
  }
  else
  {
    drawBetweenSides(sink, sides.points[West], sides.points[East], sides.points[South],
      sides.points[North], [](GridPoint p) { return p.j; });
  }
}

// The quad [i0, i1] x [j0, j1] (at least 2 quads either way) over its perimeter, which has
// every sample along the sides marked fine (in Side order) and only the corners elsewhere
// (a one-quad block beside nodata, HoleCells.h).
template <typename Sink>
void drawCellFan(Sink& sink, int i0, int j0, int i1, int j1, const bool fine[4],
  std::vector<GridPoint>& perimeter, EmitSides& sides)
{
  perimeter.clear();
  for (int i = i0; i < i1; i += fine[South] ? 1 : i1 - i0)
    perimeter.push_back({ i, j0 });
  for (int j = j0; j < j1; j += fine[East] ? 1 : j1 - j0)
    perimeter.push_back({ i1, j });
  for (int i = i1; i > i0; i -= fine[North] ? 1 : i1 - i0)
    perimeter.push_back({ i, j1 });
  for (int j = j1; j > j0; j -= fine[West] ? 1 : j1 - j0)
    perimeter.push_back({ i0, j });
  drawCellPerimeter(sink, i0, j0, i1, j1, fine, perimeter, sides);
}

// A ring block with nodata, cell by cell over its whole extent (HoleCells.h): quads with a
// nodata corner as at full resolution, cells with no vertex but their corners as drawArea
// draws them, the others over their vertices (drawCellPerimeter).
template <typename Sink>
void drawAreaAroundHoles(Sink& sink, const HoleCells& cells, std::vector<GridPoint>& perimeter,
  EmitSides& sides)
{
  for (const HoleCell& c : cells.cells)
  {
    bool inside[4];
    if (!c.nodata)
    {
      cellSidesWithVertices(cells, c, inside);
    }
    if (c.nodata || !(inside[South] || inside[East] || inside[North] || inside[West]))
    {
      sink.quad(c.i0, c.j0, c.i1, c.j1);
      continue;
    }
    // Counter-clockwise from the south-west corner, each corner once.
    perimeter.clear();
    for (int i = c.i0; i < c.i1; ++i)
      if (i == c.i0 || cells.isVertex(i, c.j0))
        perimeter.push_back({ i, c.j0 });
    for (int j = c.j0; j < c.j1; ++j)
      if (j == c.j0 || cells.isVertex(c.i1, j))
        perimeter.push_back({ c.i1, j });
    for (int i = c.i1; i > c.i0; --i)
      if (i == c.i1 || cells.isVertex(i, c.j1))
        perimeter.push_back({ i, c.j1 });
    for (int j = c.j1; j > c.j0; --j)
      if (j == c.j1 || cells.isVertex(c.i0, j))
        perimeter.push_back({ c.i0, j });
    drawCellPerimeter(sink, c.i0, c.j0, c.i1, c.j1, inside, perimeter, sides);
  }
}

// Whether `block` at `level` is drawn as cells (HoleCells.h): a block with nodata at a
// level above 0 (level 0 draws every sample anyway, with its four edges at full
// resolution: Quadtree::sideAtFullResolution).
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

// Joins the edge polyline (outer) to the inner ring polyline (inner) of one side. Both run
// in the block's counter-clockwise direction; `along` gives each point's position along
// the side. The merge advances whichever polyline's next point comes first, which cuts the
// strip into alternating fans: any edge level joins any inner level. When the next outer
// and inner points are level (a regular quad, as when both sides have the block's level),
// `innerFirst` picks the quad's diagonal: the merge then splits it along the same
// (i, j)-(i+1, j+1) diagonal as the inner grid, so that a block with its own edges draws
// one regular triangulation (at level 0, exactly the full-resolution one).
template <typename Sink, typename Along>
void drawSideStrip(Sink& sink, const std::vector<GridPoint>& outer,
  const std::vector<GridPoint>& inner, Along along, bool innerFirst)
{
  // True when the outer point at position x is to be joined before the inner one at y.
  auto outerBefore = [innerFirst](int x, int y) { return innerFirst ? x < y : x <= y; };
  std::size_t a = 0, b = 0;
  while (a + 1 < outer.size() || b + 1 < inner.size())
  {
    const bool advanceOuter = b + 1 >= inner.size() ||
      (a + 1 < outer.size() && outerBefore(along(outer[a + 1]), along(inner[b + 1])));
    if (advanceOuter)
    {
      std::size_t end = a + 1;
      while (end + 1 < outer.size() && (b + 1 >= inner.size() || outerBefore(along(outer[end + 1]), along(inner[b + 1]))))
      {
        ++end;
      }
      drawFan(sink, inner[b], outer, a, end, false);
      a = end;
    }
    else
    {
      std::size_t end = b + 1;
      while (end + 1 < inner.size() && (a + 1 < outer.size() && !outerBefore(along(outer[a + 1]), along(inner[end + 1]))))
      {
        ++end;
      }
      if (a + 1 >= outer.size())
      {
        end = inner.size() - 1;
      }
      drawFan(sink, outer[a], inner, b, end, true);
      b = end;
    }
  }
}

// The two polylines of one side strip (Tessellate.h, sidePolylines), in the block's
// counter-clockwise direction: the edge samples at the edge level (outer) and the inner
// ring's samples along that side (inner).
void sideLines(const BlockRect& r, const std::vector<int>& C, const std::vector<int>& R, int side,
  int edgeLevel, EmitScratch& scratch)
{
  std::vector<int>& edge = scratch.edge;
  std::vector<GridPoint>& outer = scratch.outer;
  std::vector<GridPoint>& inner = scratch.inner;
  outer.clear();
  inner.clear();
  const std::size_t k = C.size() - 1, L = R.size() - 1;
  switch (side)
  {
    case South:
      edgeSamples(r.i0, r.i1, edgeLevel, edge);
      for (int x : edge)
        outer.push_back({ x, r.j0 });
      for (std::size_t u = 1; u < k; ++u)
        inner.push_back({ C[u], R[1] });
      break;
    case East:
      edgeSamples(r.j0, r.j1, edgeLevel, edge);
      for (int y : edge)
        outer.push_back({ r.i1, y });
      for (std::size_t t = 1; t < L; ++t)
        inner.push_back({ C[k - 1], R[t] });
      break;
    case North:
      edgeSamples(r.i0, r.i1, edgeLevel, edge);
      for (auto it = edge.rbegin(); it != edge.rend(); ++it)
        outer.push_back({ *it, r.j1 });
      for (std::size_t u = k - 1; u >= 1; --u)
        inner.push_back({ C[u], R[L - 1] });
      break;
    default: // West
      edgeSamples(r.j0, r.j1, edgeLevel, edge);
      for (auto it = edge.rbegin(); it != edge.rend(); ++it)
        outer.push_back({ r.i0, *it });
      for (std::size_t t = L - 1; t >= 1; --t)
        inner.push_back({ C[1], R[t] });
      break;
  }
}

// The strip of one side between its two polylines (sideLines), each side's direction
// along the border and diagonal choice.
template <typename Sink>
void drawSideLines(Sink& sink, const std::vector<GridPoint>& outer, const std::vector<GridPoint>& inner,
  int side)
{
  switch (side)
  {
    case South:
      drawSideStrip(sink, outer, inner, [](GridPoint p) { return p.i; }, true);
      break;
    case East:
      drawSideStrip(sink, outer, inner, [](GridPoint p) { return p.j; }, false);
      break;
    case North:
      drawSideStrip(sink, outer, inner, [](GridPoint p) { return -p.i; }, true);
      break;
    default: // West
      drawSideStrip(sink, outer, inner, [](GridPoint p) { return -p.j; }, false);
      break;
  }
}

template <typename Sink>
void drawSide(Sink& sink, const BlockRect& r, const std::vector<int>& C,
  const std::vector<int>& R, int side, int edgeLevel, EmitScratch& scratch)
{
  sideLines(r, C, R, side, edgeLevel, scratch);
  drawSideLines(sink, scratch.outer, scratch.inner, side);
}

template <typename Sink>
void emitBlockTo(Sink& sink, const Quadtree& qt, int block, const BlockConfig& config,
  BlockPart part, EmitScratch& scratch)
{
  const BlockRect r = blockRect(qt, block);
  const BlockShape shape = blockShape(r.i1 - r.i0, r.j1 - r.j0, config.level);
  if (shape == BlockShape::OneQuad || shape == BlockShape::Thin)
  {
    if (part != BlockPart::Whole)
    {
      return;
    }
    if (shape == BlockShape::OneQuad)
    {
      bool fine[4];
      if (oneQuadFineSides(qt, block, fine))
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
  std::vector<int>& C = scratch.cols;
  std::vector<int>& R = scratch.rows;
  edgeSamples(r.i0, r.i1, config.level, C);
  edgeSamples(r.j0, r.j1, config.level, R);
  if (drawnAsHoleCells(qt, block, config.level))
  {
    // Cells over the whole block, its border included: no side strips.
    if (part == BlockPart::Whole || part == BlockPart::Inner)
    {
      buildHoleCells(qt, block, config.level, scratch.cells);
      drawAreaAroundHoles(sink, scratch.cells, scratch.inner, scratch.sides);
    }
    return;
  }
  if (part == BlockPart::Whole || part == BlockPart::Inner)
  {
    drawArea(sink, C, R);
  }
  for (int side = South; side <= West; ++side)
  {
    const bool wanted = part == BlockPart::Whole ||
      static_cast<int>(part) == static_cast<int>(BlockPart::StripSouth) + side;
    if (wanted)
    {
      drawSide(sink, r, C, R, side, config.edgeLevel[side], scratch);
    }
  }
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
  // Every vertex is a sample of the block (borders included): where it has no nodata,
  // there is nothing to drop, and the test would read each vertex's height.
  TriangleSink sink(hf, out, keepNodata || !qt.blockHasNodata[static_cast<std::size_t>(block)]);
  emitBlockTo(sink, qt, block, config, part, scratch);
}

void emitBlockGrid(const Quadtree& qt, int block, const BlockConfig& config, BlockPart part,
  std::vector<GridTriangle>& out, EmitScratch& scratch)
{
  GridSink sink(out);
  emitBlockTo(sink, qt, block, config, part, scratch);
}

void sidePolylines(const Quadtree& qt, int block, const BlockConfig& config, int side,
  EmitScratch& scratch)
{
  const BlockRect r = blockRect(qt, block);
  edgeSamples(r.i0, r.i1, config.level, scratch.cols);
  edgeSamples(r.j0, r.j1, config.level, scratch.rows);
  sideLines(r, scratch.cols, scratch.rows, side, config.edgeLevel[side], scratch);
}

void emitSidePolylinesGrid(const EmitScratch& lines, int side, std::vector<GridTriangle>& out)
{
  GridSink sink(out);
  drawSideLines(sink, lines.outer, lines.inner, side);
}

BlockConfig blockConfigOf(const Quadtree& qt, const std::vector<int8_t>& levels, int block)
{
  BlockConfig cfg;
  cfg.level = levels[block];
  const std::array<int, 4> neighbour = qt.blockNeighbours(block);
  const int top = topLevel(qt.blockWidth(block), qt.blockHeight(block));
  for (int side = 0; side < 4; ++side)
  {
    const int nb = neighbour[side];
    if (qt.sideAtFullResolutionBeside(block, nb))
    {
      cfg.edgeLevel[side] = 0; // beside nodata: every sample, whatever the levels
      continue;
    }
    int nl = nb >= 0 ? levels[nb] : -1;
    if (nl == kCoveredLevel)
    {
      nl = top; // corners only, as the merged node's perimeter has them
    }
    cfg.edgeLevel[side] = nl > cfg.level ? nl : cfg.level;
  }
  return cfg;
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
      emitBlock(hf, qt, b, blockConfigOf(qt, levels, b), BlockPart::Whole, out, scratch);
    }
  }
  for (int n : merged)
  {
    emitMergedNode(hf, qt, n, out, scratch);
  }
}

} // namespace gmm
