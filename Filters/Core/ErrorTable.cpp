#include "ErrorTable.h"

#include "CoarsePerimeter.h"
#include "FanMorph.h"

#include "HugePages.h"
#include "Levels.h"
#include "Parallel.h"
#include "RasterError.h"
#include "Tessellate.h"
#include "TriangleCount.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <atomic>
#include <chrono>
#include <thread>

namespace gmm
{

namespace
{
constexpr float kInf = std::numeric_limits<float>::infinity();

// Buffers one worker reuses for every part it rasterises.
struct Scratch
{
  std::vector<GridTriangle> triangles;
  EmitScratch emit;
  // Errors of the current block's strip lines, measured once per block (NaN: not yet):
  // the edge polyline per side and edge level, which every ring level's strip towards that
  // edge level shares, and the inner ring's polyline per side and ring level.
  std::vector<float> edgeLine, ringLine;
  FanMorphScratch fan;
  CoarsePerimeterScratch perimeter;
};

float partError(const Heightfield& hf, const Quadtree& qt, int block, const BlockConfig& cfg,
  BlockPart part, bool strict, Scratch& scratch)
{
  scratch.triangles.clear();
  emitBlockGrid(qt, block, cfg, part, scratch.triangles, scratch.emit);
  return trianglesError(hf, scratch.triangles, strict);
}

// Error of one side strip of a ring block (strict: nodata gives +inf). Its samples on the
// edge line and on the inner ring's line are interpolations along those polylines, and
// measured so, once per block and line (Scratch); only the rows (or columns) strictly
// between the lines are rasterised: none at level 0, where the lines are adjacent, one at
// level 1. Rasterising every strip triangle whole cost most of the table at small blocks:
// a level-0 strip's triangles cover two or three samples each, all on the lines, and
// every ring level measured the edge line again for each edge level. Measured at 4097^2,
// block 32, one thread on one core: the table in 0.70 s against 0.99 s.
// With a glided edge (cfg.sampleLevel[side] >= 0: the block's own cells up to its border,
// their samples there drawn on the polyline at cfg.edgeLevel[side]), the edge line is that
// polyline and the strip's triangles are rasterised with those vertices on it.
float sideStripError(const Heightfield& hf, const Quadtree& qt, int block, const BlockConfig& cfg,
  int side, Scratch& scratch, const HoleCells* cells)
{
  const std::size_t levels = scratch.edgeLine.size() / 4;
  float& edge = scratch.edgeLine[side * levels + cfg.edgeLevel[side]];
  if (std::isnan(edge))
  {
    edge = sidePolylineError(hf, qt, block, side, cfg.edgeLevel[side], scratch.emit);
  }
  sidePolylines(qt, block, cfg, side, scratch.emit, cells);
  const std::vector<GridPoint>& outer = scratch.emit.outer;
  const std::vector<GridPoint>& inner = scratch.emit.inner;
  float& ring = scratch.ringLine[side * levels + cfg.level];
  if (std::isnan(ring))
  {
    ring = polylineError(hf, inner);
  }
  const float lines = std::max(edge, ring);
  const bool rows = side == South || side == North;
  const int lineA = rows ? outer[0].j : outer[0].i, lineB = rows ? inner[0].j : inner[0].i;
  if (lines == kInf || std::abs(lineB - lineA) <= 1)
  {
    return lines; // nothing strictly between the lines
  }
  scratch.triangles.clear();
  emitSidePolylinesGrid(scratch.emit, side, scratch.triangles);
  if (cfg.sampleLevel[side] >= 0)
  {
    const int c = block % qt.blockCols, r = block / qt.blockCols;
    const GlidedLine glide{ rows, lineA, rows ? qt.colStart[c] : qt.rowStart[r],
      rows ? qt.colStart[c + 1] : qt.rowStart[r + 1], cfg.edgeLevel[side] };
    return std::max(lines, stripInteriorError(hf, scratch.triangles, rows, lineA, lineB, &glide));
  }
  return std::max(lines, stripInteriorError(hf, scratch.triangles, rows, lineA, lineB));
}

void fillBlock(const Heightfield& hf, const Quadtree& qt, int block, ErrorTable& t,
  Scratch& scratch)
{
  const int width = qt.blockWidth(block), height = qt.blockHeight(block);
  const int top = topLevel(width, height);
  float* own = &t.ownError[static_cast<std::size_t>(block) * t.levels];
  float* exact = &t.ownErrorExact[static_cast<std::size_t>(block) * t.levels];
  float* strips = &t.stripError[static_cast<std::size_t>(block) * 4 * t.pairs];
  const bool nodata = qt.blockHasNodata[block] != 0;
  const bool empty = qt.everySampleNodata(block);
  const std::array<int, 4> neighbour = qt.blockNeighbours(block);
  std::array<bool, 4> fine{}; // may be drawn at full resolution (with the levels or always)
  for (int side = 0; side < 4; ++side)
  {
    fine[side] = qt.sideAtFullResolutionBeside(block, neighbour[side]);
  }
  scratch.edgeLine.assign(4 * static_cast<std::size_t>(t.levels), std::numeric_limits<float>::quiet_NaN());
  scratch.ringLine.assign(4 * static_cast<std::size_t>(t.levels), std::numeric_limits<float>::quiet_NaN());
  float running = 0.0f;
  std::size_t fewest = std::numeric_limits<std::size_t>::max(); // triangles, for nodata
  for (int m = 0; m < t.levels; ++m)
  {
    const BlockShape shape = blockShape(width, height, m);
    own[m] = exact[m] = kInf;
    if (m > top || shape == BlockShape::Invalid || running == kInf)
    {
      // Never selected: an invalid shape, or a finer level already met nodata (+inf),
      // which every coarser level then does too (own errors are monotone).
      continue;
    }
    // Full resolution with its own edges draws every sample: holes there are the data's.
    const bool strict = m > 0;
    // Per side: whether it is always at full resolution at m (fullOnly: the block or its
    // neighbour holds nodata, and one of them never follows the edge levels there), or is
    // at full resolution or not with the neighbour's level (bothWays,
    // Quadtree::sideAtFullResolutionAt), which its own error covers both ways while its
    // strips towards coarser edges are measured as for any side.
    std::array<bool, 4> fullOnly{}, bothWays{};
    BlockConfig cfg; // its own edges: the level, or every sample where nothing else is drawn
    cfg.level = m;
    for (int side = 0; side < 4; ++side)
    {
      const int nb = neighbour[side];
      fullOnly[side] = fine[side] &&
        !(qt.followsEdgeLevels(block, side, m) && (nb < 0 || qt.mayFollowEdgeLevels(nb, (side + 2) % 4)));
      bothWays[side] = fine[side] && !fullOnly[side] && nb >= 0 && m > 0;
      cfg.edgeLevel[side] = fullOnly[side] ? 0 : m;
    }
    // Level 0 with its own edges has every sample as a vertex: its error is exactly 0
    // (a vertex's residual is (zb - za) * A - A * (zb - za) = 0 in double), so only its
    // strips towards coarser edges are rasterised.
    float e = 0.0f;
    if (shape != BlockShape::Ring)
    {
      // One quad (or thin): one cell over its perimeter, which is not drawn in parts, so
      // every combination of its sides drawn both ways (beside blocks with nodata).
      std::array<int, 4> both{};
      int bothCount = 0;
      for (int side = 0; side < 4; ++side)
      {
        if (bothWays[side])
        {
          both[bothCount++] = side;
        }
      }
      for (int mask = 0; m > 0 && mask < (1 << bothCount); ++mask)
      {
        BlockConfig combination = cfg;
        for (int k = 0; k < bothCount; ++k)
        {
          combination.edgeLevel[both[k]] = (mask >> k) & 1 ? 0 : m;
        }
        e = std::max(e, partError(hf, qt, block, combination, BlockPart::Whole, strict, scratch));
      }
    }
    else
    {
      // A block with nodata above level 0 is cells around it (HoleCells.h), and side strips
      // only where a side's border row is clear of it: only full-resolution cells touch
      // nodata, and they are the data's own holes (not strict); its strips join the cells'
      // vertices (sidePolylines) and cross no nodata (strict). A block with no valid sample
      // (the sea beside a coast) draws nothing: error 0, not rasterised.
      const HoleCells* cells = nullptr;
      if (nodata && m > 0)
      {
        buildHoleCells(qt, block, m, scratch.emit.cells);
        cells = &scratch.emit.cells;
      }
      for (int side = 0; side < 4 && !empty; ++side)
      {
        if (cells && !cells->strip[side])
        {
          continue; // the cells reach the border there
        }
        float previous = m == 0 ? 0.0f : sideStripError(hf, qt, block, cfg, side, scratch, cells);
        e = std::max(e, previous);
        if (bothWays[side])
        {
          BlockConfig full = cfg;
          full.edgeLevel[side] = 0;
          e = std::max(e, sideStripError(hf, qt, block, full, side, scratch, cells));
        }
        if (fullOnly[side])
        {
          continue; // no coarser edge: strips[] for this side stay unused (0)
        }
        // Coarser edges: from the first coarser level until the edge is just its corners;
        // beyond that the strip no longer changes. A coarser block across glides the edge
        // (its samples at m drawn on its polyline at n, BlockConfig::sampleLevel); a merged
        // node across has the block's corners only, at its top level, which its strip fans
        // to: that entry holds both.
        const int edgeLength = (side == South || side == North) ? width : height;
        for (int n = m + 1; n < t.levels; ++n)
        {
          const bool changes = ((1LL << (n - 1)) < edgeLength);
          float s = previous;
          if (changes || n == top)
          {
            BlockConfig coarse = cfg;
            coarse.edgeLevel[side] = n;
            coarse.sampleLevel[side] = m;
            s = std::max(previous, sideStripError(hf, qt, block, coarse, side, scratch, cells));
            if (n == top)
            {
              coarse.sampleLevel[side] = -1;
              s = std::max(s, sideStripError(hf, qt, block, coarse, side, scratch, cells));
            }
          }
          strips[side * t.pairs + ErrorTable::pairIndex(m, n)] = s;
          previous = s;
        }
      }
      // The inner grid (or cells) after the strips: a strip over nodata (+inf) makes it moot.
      if (m > 0 && e != kInf && !empty)
      {
        if (cells)
        {
          // The cells built above (their nodata quads are the data's holes: not strict).
          scratch.triangles.clear();
          emitHoleCellsGrid(*cells, scratch.triangles, scratch.emit);
          e = std::max(e, trianglesError(hf, scratch.triangles, false));
        }
        else
        {
          edgeSamples(qt.colStart[block % qt.blockCols], qt.colStart[block % qt.blockCols + 1], m, scratch.emit.cols);
          edgeSamples(qt.rowStart[block / qt.blockCols], qt.rowStart[block / qt.blockCols + 1], m, scratch.emit.rows);
          e = std::max(e, innerAreaError(hf, scratch.emit.cols, scratch.emit.rows));
        }
      }
    }
    exact[m] = e;
    running = std::max(running, e);
    own[m] = running; // monotone over the valid levels
    if (nodata && shape == BlockShape::Ring)
    {
      // A block with nodata does not draw fewer triangles at every coarser level (its
      // cells may split into the same pieces as a finer level's, HoleCells.h). A level
      // with no fewer triangles than a finer allowed one, whose error is no larger, is
      // never worth drawing: not allowed.
      const std::size_t count = blockTriangleCount(qt, block, cfg, &t); // cellTriangles above 0
      if (count >= fewest)
      {
        own[m] = kInf;
      }
      fewest = std::min(fewest, count);
    }
  }
}

// A merged node's fan over every sample of the node; nodata anywhere below it is +inf
// (the fan would draw over the hole). Nodes whose error is not computed exactly
// (mergedErrorIsExact) get a bound instead: every fan vertex is a sample of the node, so
// the fan lies within the node's height range and no sample is further from it than that
// range. Such nodes are drawn only from far away, and computing their fans exactly would
// cost the table one more pass over every sample per level.
float mergedNodeError(const Heightfield& hf, const Quadtree& qt, int node, Scratch& scratch)
{
  if (!mergeableNode(qt, node))
  {
    return kInf;
  }
  const QuadtreeNode& n = qt.nodes[node];
  if (!mergedErrorIsExact(qt, node))
  {
    for (int r = n.rowBegin; r < n.rowEnd; ++r)
      for (int c = n.colBegin; c < n.colEnd; ++c)
        if (qt.blockHasNodata[qt.blockIndex(c, r)])
          return kInf;
    return roundUpToFloat(n.box.hi.z - n.box.lo.z);
  }
  scratch.triangles.clear();
  emitMergedNodeGrid(qt, node, scratch.triangles);
  return trianglesError(hf, scratch.triangles, true);
}

} // namespace

void fillCellTriangles(const Quadtree& qt, ErrorTable& table, int threads)
{
  table.cellTriangles.clear();
  if (qt.nodataBits.empty())
  {
    return;
  }
  table.cellTriangles.assign(static_cast<std::size_t>(qt.blockCount()) * table.levels, 0);
  parallelChunks(static_cast<std::size_t>(qt.blockCount()), 256, threads,
    [&](std::size_t begin, std::size_t end) {
      HoleCells cells;
      for (int b = static_cast<int>(begin); b < static_cast<int>(end); ++b)
      {
        const int w = qt.blockWidth(b), h = qt.blockHeight(b);
        for (int m = 0; qt.blockHasNodata[b] && m < table.levels; ++m)
        {
          if (blockShape(w, h, m) != BlockShape::Ring)
          {
            continue;
          }
          std::size_t n = 0;
          if (m == 0)
          {
            BlockConfig full; // level 0, every side at full resolution (followsEdgeLevels)
            n = drawnTriangleCount(qt, b, full);
          }
          else
          {
            buildHoleCells(qt, b, m, cells);
            n = holeCellsTriangleCount(cells);
          }
          table.cellTriangles[static_cast<std::size_t>(b) * table.levels + m] = static_cast<uint32_t>(n);
        }
      }
    });
}

bool mergedErrorIsExact(const Quadtree& qt, int node)
{
  const QuadtreeNode& n = qt.nodes[node];
  const int quads = std::max(qt.colStart[n.colEnd] - qt.colStart[n.colBegin],
    qt.rowStart[n.rowEnd] - qt.rowStart[n.rowBegin]);
  return n.height <= kExactMergedHeight || quads <= kExactMergedQuads;
}

ErrorTable buildErrorTable(const Heightfield& hf, const Quadtree& qt, int threads,
  const std::function<void(double)>& progress)
{
  ErrorTable t;
  int maxTop = 0;
  for (int b = 0; b < qt.blockCount(); ++b)
  {
    maxTop = std::max(maxTop, topLevel(qt.blockWidth(b), qt.blockHeight(b)));
  }
  t.levels = maxTop + 1;
  t.pairs = t.levels * (t.levels - 1) / 2;
  const std::size_t blocks = static_cast<std::size_t>(qt.blockCount());
  t.ownError.clear();
  t.ownErrorExact.clear();
  t.stripError.clear();
  t.mergedError.clear();
  resizeOnHugePages(t.ownError, blocks * t.levels, kInf);
  resizeOnHugePages(t.ownErrorExact, blocks * t.levels, kInf);
  resizeOnHugePages(t.stripError, blocks * 4 * std::max(1, t.pairs), 0.0f);

  const std::size_t nodes = qt.nodes.size();
  resizeOnHugePages(t.mergedError, nodes, kInf);
  for (std::vector<float>* v : { &t.fanResidual, &t.fanMovedError, &t.fanChildrenError })
  {
    v->assign(nodes, kInf);
  }
  perimeterOffsets(qt, t.perimeterFirst);
  t.perimeterError.assign(t.perimeterFirst.back(), kInf);
  t.perimeterPop.assign(t.perimeterFirst.back(), kInf);
  // Before the blocks: their levels' triangle counts decide which levels are allowed.
  fillCellTriangles(qt, t, threads);
  // Work items: every block, then every quadtree node (its merged fan).
  const std::size_t items = blocks + nodes;

  const unsigned workers = workerCount(threads, items);
  // Items are independent. Workers take the next ones from a shared counter rather than a
  // fixed share, so that a worker on a slower or busier core does fewer: with a fixed
  // interleaving the build took as long as its slowest half, and on this project's 2-core
  // VM one core builds the table 1.65x slower than the other (16385^2: 10.7 s with two
  // threads against 11.7 s with one). Blocks go in runs of kBlockRun (neighbours share
  // cache lines of heights and table); merged nodes one at a time, as one near the top
  // covers up to 16 x 16 blocks.
  constexpr std::size_t kBlockRun = 16;
  std::atomic<std::size_t> nextBlock{ 0 }, nextNode{ 0 }, done{ 0 };
  auto work = [&]() {
    Scratch scratch;
    for (std::size_t first; (first = nextBlock.fetch_add(kBlockRun)) < blocks;)
    {
      const std::size_t last = std::min(blocks, first + kBlockRun);
      for (std::size_t b = first; b < last; ++b)
        fillBlock(hf, qt, static_cast<int>(b), t, scratch);
      done.fetch_add(last - first, std::memory_order_relaxed);
    }
    for (std::size_t n; (n = nextNode.fetch_add(1)) < nodes;)
    {
      t.mergedError[n] = mergedNodeError(hf, qt, static_cast<int>(n), scratch);
      const FanMorphErrors fan = fanMorphErrors(hf, qt, static_cast<int>(n), scratch.fan);
      t.fanResidual[n] = fan.residual;
      t.fanMovedError[n] = fan.moved;
      t.fanChildrenError[n] = fan.children;
      const uint32_t first = t.perimeterFirst[n];
      coarsePerimeterErrors(hf, qt, static_cast<int>(n), scratch.perimeter, t.perimeterError.data() + first,
        t.perimeterPop.data() + first);
      done.fetch_add(1, std::memory_order_relaxed);
    }
  };
  std::vector<std::thread> pool;
  for (unsigned w = 0; w < workers; ++w)
  {
    pool.emplace_back(work);
  }
  if (progress)
  {
    // The caller's thread reports (VTK progress events must come from it) while it waits.
    // Short waits first, so that a small table is not held up by the polling.
    for (int wait = 1; done.load(std::memory_order_relaxed) < items; wait = std::min(2 * wait, 50))
    {
      progress(static_cast<double>(done.load(std::memory_order_relaxed)) / items);
      std::this_thread::sleep_for(std::chrono::milliseconds(wait));
    }
    progress(1.0);
  }
  for (std::thread& th : pool)
  {
    th.join();
  }
  return t;
}

} // namespace gmm
