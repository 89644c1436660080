// Geomorphing's factors for a frame (Morph.h, computeMorph): targets, edges, the part
// errors kept and measured, and the factors within the certificate and the path. Where the
// vertices go at those factors: MorphTargets.cpp.
#include "Morph.h"

#include "FanMorph.h"

#include "Levels.h"
#include "MorphFactors.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gmm
{

double diagonalReach(const double e[4], double limit)
{
  // Along the diagonal the bound is the parabola q(t) = c + t (b + t a); [0, t] is within
  // limit while t is at most q's first crossing of limit. That root is solved for, then
  // stepped down until the test itself holds (rounding), so the answer is never above the
  // largest certified factor. A bisection did the same in 50 steps of the test.
  const double c = e[0], b = e[1] + e[2] - 2.0 * e[0], a = e[0] - e[1] - e[2] + e[3];
  auto q = [&](double t) { return c + t * (b + t * a); };
  const double vertex = a < 0.0 ? -b / (2.0 * a) : -1.0;
  auto ok = [&](double t) { return q(t) <= limit && !(vertex > 0.0 && vertex < t && q(vertex) > limit); };
  if (ok(1.0))
  {
    return 1.0;
  }
  if (!ok(0.0))
  {
    return 0.0;
  }
  // Smallest root in (0, 1] of a t^2 + b t + (c - limit) = 0 (one exists: q(0) <= limit <
  // q somewhere in (0, 1]); the stable pair of roots, or the linear one.
  const double k = c - limit;
  double t = 1.0;
  if (a == 0.0)
  {
    t = b > 0.0 ? -k / b : 1.0;
  }
  else
  {
    const double disc = std::max(b * b - 4.0 * a * k, 0.0);
    const double qq = -0.5 * (b + std::copysign(std::sqrt(disc), b));
    for (const double r : { qq / a, qq != 0.0 ? k / qq : 1.0 })
    {
      if (r > 0.0 && r < t)
      {
        t = r;
      }
    }
  }
  t = std::min(std::max(t, 0.0), 1.0);
  for (int step = 0; step < 8 && t > 0.0 && !ok(t); ++step)
  {
    t = std::nextafter(t, 0.0); // the root's rounding
  }
  if (ok(t))
  {
    return t;
  }
  double lo = 0.0, hi = t; // rounding worse than a few ulps: bisect below the root
  for (int n = 0; n < 50; ++n)
  {
    const double mid = 0.5 * (lo + hi);
    (ok(mid) ? lo : hi) = mid;
  }
  return lo;
}

namespace
{
// blockEdges of a frame being written.
std::array<MorphEdge*, 4> edgesOf(const Quadtree& qt, MorphFrame& f, int block)
{
  const std::array<const MorphEdge*, 4> e = blockEdges(qt, f, block);
  return { const_cast<MorphEdge*>(e[0]), const_cast<MorphEdge*>(e[1]), const_cast<MorphEdge*>(e[2]),
    const_cast<MorphEdge*>(e[3]) };
}
} // namespace

std::array<const MorphEdge*, 4> blockEdges(const Quadtree& qt, const MorphFrame& f, int block)
{
  const int bc = qt.blockCols, c = block % bc, r = block / bc;
  return { &f.hEdges[static_cast<std::size_t>(r) * bc + c],
    &f.vEdges[static_cast<std::size_t>(r) * (bc + 1) + c + 1],
    &f.hEdges[static_cast<std::size_t>(r + 1) * bc + c],
    &f.vEdges[static_cast<std::size_t>(r) * (bc + 1) + c] };
}

void clearMorph(const Quadtree& qt, MorphFrame& out)
{
  out.blockT.assign(qt.blockCount(), 0.0f);
  out.blockTarget.assign(qt.blockCount(), -1);
  out.vEdges.assign(static_cast<std::size_t>(qt.blockCols + 1) * qt.blockRows, MorphEdge());
  out.hEdges.assign(static_cast<std::size_t>(qt.blockCols) * (qt.blockRows + 1), MorphEdge());
  out.cornerT.assign(static_cast<std::size_t>(qt.blockCols + 1) * (qt.blockRows + 1), 0.0f);
  out.cornerTarget.assign(out.cornerT.size(), 0.0f);
  out.corners.clear();
  out.blocks.clear();
  out.maxBoundPixels = 0.0;
}

namespace
{
// Back to no morphing, touching only what the last frame set (its blocks and their edges):
// a frame costs what it draws, not the DEM. A frame of another quadtree starts afresh.
void resetMorph(const Quadtree& qt, MorphFrame& out)
{
  if (out.blockT.size() != static_cast<std::size_t>(qt.blockCount()) ||
    out.vEdges.size() != static_cast<std::size_t>(qt.blockCols + 1) * qt.blockRows ||
    out.hEdges.size() != static_cast<std::size_t>(qt.blockCols) * (qt.blockRows + 1) ||
    out.cornerT.size() != static_cast<std::size_t>(qt.blockCols + 1) * (qt.blockRows + 1))
  {
    clearMorph(qt, out);
    return;
  }
  for (int k : out.corners)
  {
    out.cornerT[k] = 0.0f;
    out.cornerTarget[k] = 0.0f;
  }
  out.corners.clear();
  for (int b : out.blocks)
  {
    out.blockT[b] = 0.0f;
    out.blockTarget[b] = -1;
    for (MorphEdge* e : edgesOf(qt, out, b))
    {
      *e = MorphEdge();
    }
  }
  out.blocks.clear();
  out.maxBoundPixels = 0.0;
}
} // namespace

namespace
{
// The drawn blocks into `drawn`: the caller's list, or found in the levels.
void listDrawn(const std::vector<int8_t>& levels, const std::vector<int>* drawnBlocks, std::vector<int>& drawn)
{
  if (drawnBlocks)
  {
    drawn = *drawnBlocks;
    return;
  }
  drawn.clear();
  for (int b = 0; b < static_cast<int>(levels.size()); ++b)
  {
    if (levels[b] >= 0)
    {
      drawn.push_back(b);
    }
  }
}

// A drawn block's edges at the levels Tessellate draws them with: the coarser of two drawn
// blocks (both sides agree), the block's top level beside a merged node (corners only:
// nothing on the edge moves, and the node's fan keeps its perimeter still), 0 on a side at
// full resolution.
void setEdgeLevels(const BlockConfig& config, const std::array<MorphEdge*, 4>& edges)
{
  for (int side = 0; side < 4; ++side)
  {
    edges[side]->level = static_cast<int8_t>(std::max<int>(edges[side]->level, config.edgeLevel[side]));
  }
}

// Gives every drawn block a slot (keeping the one it held last frame) and takes the slots
// back from the blocks no longer drawn.
void assignSlots(const std::vector<int>& drawn, MorphCache& cache)
{
  ++cache.frame;
  cache.drawnSlots.resize(drawn.size());
  for (std::size_t k = 0; k < drawn.size(); ++k)
  {
    const int b = drawn[k];
    int32_t& s = cache.slotOf[b];
    if (s < 0)
    {
      if (cache.freeSlots.empty())
      {
        s = static_cast<int32_t>(cache.slots.size());
        cache.slots.emplace_back();
      }
      else
      {
        s = cache.freeSlots.back();
        cache.freeSlots.pop_back();
        cache.slots[s] = MorphBlockState();
      }
      cache.slots[s].block = b;
    }
    cache.slots[s].frame = cache.frame;
    cache.drawnSlots[k] = s;
  }
  for (const int32_t s : cache.held)
  {
    MorphBlockState& state = cache.slots[s];
    if (state.frame != cache.frame)
    {
      cache.slotOf[state.block] = -1;
      cache.freeSlots.push_back(s);
    }
  }
  cache.held = cache.drawnSlots;
}
} // namespace

void drawnEdgeFrame(const Quadtree& qt, const std::vector<int8_t>& levels, MorphFrame& out,
  const std::vector<int>* drawnBlocks, const std::vector<BlockConfig>* drawnConfigs)
{
  resetMorph(qt, out);
  listDrawn(levels, drawnBlocks, out.blocks);
  const bool ownConfigs = drawnConfigs && drawnConfigs->size() == static_cast<std::size_t>(qt.blockCount());
  for (int b : out.blocks)
  {
    setEdgeLevels(ownConfigs ? (*drawnConfigs)[b] : blockConfigOf(qt, levels, b), edgesOf(qt, out, b));
  }
}

void computeMorph(const Heightfield& hf, const Quadtree& qt, const std::vector<int8_t>& levels,
  const std::vector<double>& factor, double tau, MorphCache& cache, MorphFrame& out,
  const MorphRamp* ramp, const std::vector<int>* drawnBlocks, const std::vector<BlockConfig>* drawnConfigs,
  const ErrorTable* table)
{
  resetMorph(qt, out);
  const int blocks = qt.blockCount();
  if (cache.heights != hf.heights() || static_cast<int>(cache.slotOf.size()) != blocks)
  {
    cache.slotOf.assign(blocks, -1);
    cache.slots.clear();
    cache.freeSlots.clear();
    cache.held.clear();
    cache.inner.reset(blocks);
    cache.polylines.reset(blocks);
    cache.fanCorners.reset(qt.nodes.size());
    cache.heights = hf.heights();
  }
  std::vector<int>& drawn = out.blocks;
  listDrawn(levels, drawnBlocks, drawn);
  cache.firstFrame = cache.held.empty();
  assignSlots(drawn, cache);
  const bool limited = ramp && ramp->active();
  const double slope = limited ? ramp->slope() : 0.0;
  // Per drawn block: the stored-height error its factor allows (tau / factor), -1 when it
  // does not morph (not in view).
  std::vector<double>& budget = cache.budgets;
  budget.resize(drawn.size());
  for (std::size_t k = 0; k < drawn.size(); ++k)
  {
    const int b = drawn[k];
    const double f = b < static_cast<int>(factor.size()) ? factor[b] : 0.0;
    budget[k] = std::isfinite(f) && f > 0.0 ? tau / f : -1.0;
  }

  // Edge levels and targets: an edge takes the level of the coarser block (Tessellate) and
  // moves toward the next level of the block(s) that set it.
  // A block with nodata never morphs: every nodata sample lies in one of its cells'
  // full-resolution quads (HoleCells.h), which morphPartErrors freezes, so it gets no
  // target and its parts are not measured (with side strips, a changed configuration
  // built its cells once for each of its five parts).
  for (int b : drawn)
  {
    const int m = levels[b];
    const int w = qt.blockWidth(b), h = qt.blockHeight(b);
    if (blockShape(w, h, m) == BlockShape::Ring && !qt.blockHasNodata[b])
    {
      out.blockTarget[b] = static_cast<int8_t>(nextValidLevel(w, h, m));
    }
  }
  // The caller's configurations when they are one per block of this quadtree.
  const bool ownConfigs = drawnConfigs && drawnConfigs->size() == static_cast<std::size_t>(blocks);
  std::vector<BlockConfig>& configs = cache.configs;
  std::vector<std::array<MorphEdge*, 4>>& drawnEdges = cache.edges;
  configs.resize(drawn.size());
  drawnEdges.resize(drawn.size());
  for (std::size_t k = 0; k < drawn.size(); ++k)
  {
    const int b = drawn[k];
    configs[k] = ownConfigs ? (*drawnConfigs)[b] : blockConfigOf(qt, levels, b);
    drawnEdges[k] = edgesOf(qt, out, b);
    setEdgeLevels(configs[k], drawnEdges[k]);
  }
  for (std::size_t k = 0; k < drawn.size(); ++k)
  {
    const int b = drawn[k];
    if (out.blockTarget[b] < 0)
    {
      continue;
    }
    for (int side = 0; side < 4; ++side)
    {
      // A side at full resolution has every sample whatever the levels: nothing on it moves.
      MorphEdge* e = drawnEdges[k][side];
      if (e->level == levels[b] && !qt.sideAtFullResolution(b, side))
      {
        e->target = e->target < 0 ? out.blockTarget[b] : std::min(e->target, out.blockTarget[b]);
      }
    }
  }

  // Block factors: the inner grid, and the strips whose edge the block sets moving with it
  // (and with the edge held, so that any lower edge factor stays certified too).
  // morphs[k]: drawn[k] morphs, and its slot's errors are this frame's.
  std::vector<uint8_t>& morphs = cache.morphs;
  morphs.assign(drawn.size(), 0);
  // Each drawn block's level as an index into its chain (MorphRamp.h), for the rise limit
  // and its history.
  std::vector<int>& chainAt = cache.chainAt;
  chainAt.assign(drawn.size(), 0);
  if (limited)
  {
    for (std::size_t k = 0; k < drawn.size(); ++k)
    {
      chainAt[k] = chainIndex(qt, drawn[k], levels[drawn[k]]);
    }
  }
  refreshPartErrors(hf, qt, out, cache, table);
  for (std::size_t k = 0; k < drawn.size(); ++k)
  {
    const int b = drawn[k];
    MorphBlockState& state = cache.slots[cache.drawnSlots[k]];
    if (out.blockTarget[b] < 0 || budget[k] < 0.0 || cache.deferred[k] == kMorphHeld)
    {
      continue;
    }
    const BlockConfig& cfg = configs[k];
    const std::array<MorphEdge*, 4>& edges = drawnEdges[k];
    const PartErrors& pe = state.errors;
    morphs[k] = 1;
    const double x = budget[k];
    // The inner grid with its edges held: a block factor that does not fit once they move
    // is lowered below, after the edges are fitted.
    double t = pe.innerFrozen ? 0.0 : innerReach(pe, { 0.0, 0.0, 0.0, 0.0 }, x);
    for (int side = 0; side < 4; ++side)
    {
      const double* e = pe.side[side];
      if (pe.sideFrozen[side])
      {
        t = 0.0;
        continue;
      }
      t = std::min(t, linearReach(e[0], e[1], x)); // edge held (e = 0)
      if (edges[side]->level == cfg.level && edges[side]->target >= 0)
      {
        t = std::min(t, diagonalReach(e, x)); // edge moving with the block
      }
    }
    // The level path (MorphRamp.h): a block at its path's level morphs no further than the
    // path, so that it reaches factor 0 where the path refines it and 1 where it coarsens.
    if (limited && ramp->level[b] == levels[b])
    {
      t = std::min(t, static_cast<double>(ramp->factor[b]));
    }
    // The rise limit: the drawn continuous level rises no faster than the path may. Any
    // lower factor keeps the certificate (every part's bound holds on [0, t]), and the edge
    // factors below are fitted to the factor chosen here.
    // The logarithm only where the limit can bind: the rise is at least the settle term.
    const double fPrev = state.lastFactor, lambdaPrev = state.lastLambda;
    if (limited && lambdaPrev >= 0.0 && fPrev > 0.0)
    {
      const double below = lambdaPrev - chainAt[k];
      if (t > below + kMorphSettlePerFrame)
      {
        // The path rises only as the block recedes (its budget grows); a rise while it
        // comes nearer is a constraint let go (a neighbour's strip, an edge), taken at
        // kMorphRisePixels a frame.
        const double receding = factor[b] < fPrev ? slope * std::log(fPrev / factor[b]) : 0.0;
        const double rise = std::min(slope * std::fabs(std::log(factor[b] / fPrev)) + kMorphSettlePerFrame,
          receding + risePixels(pe, -1, factor[b]));
        t = std::min(t, std::max(0.0, below + rise));
      }
    }
    out.blockT[b] = factorDown(t);
  }

  // Edge factors, then the blocks and edges fitted to each other (MorphFactors.h); the rules
  // that read the last frame's factors only on the path, which keeps that history.
  fitEdgeFactors(levels, cache, out);
  if (limited)
  {
    yieldToCoarserEdges(qt, levels, factor, cache, out);
  }
  fitInnerGridsToEdges(levels, cache, out);
  if (limited)
  {
    limitEdgeRises(levels, factor, cache, out);
  }

  for (std::size_t k = 0; k < drawn.size(); ++k)
  {
    if (!morphs[k])
    {
      continue;
    }
    const int b = drawn[k];
    const PartErrors& pe = cache.slots[cache.drawnSlots[k]].errors;
    const double tb = out.blockT[b];
    const std::array<MorphEdge*, 4>& edges = drawnEdges[k];
    double bound = (1.0 - tb) * pe.inner[0] + tb * pe.inner[1]; // every edge at its worst
    if (bound * factor[b] > out.maxBoundPixels)
    {
      bound = innerBound(pe, edgeFactors(edges), tb); // at the edges' factors: no larger
    }
    for (int side = 0; side < 4; ++side)
    {
      bound = std::max(bound, stripBound(pe.side[side], edges[side]->t, tb));
    }
    out.maxBoundPixels = std::max(out.maxBoundPixels, bound * factor[b]);
  }
  if (ramp)
  {
    applyFanMorph(hf, qt, ramp->premerging, cache.fanCorners, out);
  }
  // History for the next frame's rise limit: none from a frame without the path, nor for a
  // block whose factor came from bounds its measurement will replace (refreshPartErrors,
  // past the frame's measuring limit): it takes the measured factor when it has it, instead
  // of rising to it from the smaller one over many frames, behind its level path.
  for (std::size_t k = 0; k < drawn.size(); ++k)
  {
    const int b = drawn[k];
    MorphBlockState& state = cache.slots[cache.drawnSlots[k]];
    const bool keep = limited && b < static_cast<int>(factor.size()) && cache.deferred[k] == kMorphMeasured;
    state.lastLambda = keep ? chainAt[k] + out.blockT[b] : -1.0;
    state.lastFactor = keep ? factor[b] : 0.0;
    for (int side = 0; side < 4; ++side)
    {
      state.lastEdges[side] = keep ? *cache.edges[k][side] : MorphEdge();
    }
  }
}

unsigned changedMorphParts(const std::array<int8_t, 10>& was, const std::array<int8_t, 10>& now)
{
  if (was[0] != now[0] || was[5] != now[5])
  {
    return kAllMorphParts;
  }
  const int target = now[5];
  unsigned parts = 0;
  for (int side = 0; side < 4; ++side)
  {
    if (was[1 + side] != now[1 + side] || was[6 + side] != now[6 + side])
    {
      parts |= 2u << side;
    }
    // The target's samples on that side are where the edge draws them (its polyline when
    // coarser than the target, moving when the edge moves), which the inner grid's and the
    // two neighbouring strips' ring vertices move toward near it (blockVertexTarget).
    const int levelWas = was[1 + side] & 31, levelNow = now[1 + side] & 31;
    const bool moves = was[6 + side] >= 0 || now[6 + side] >= 0;
    if ((was[1 + side] != now[1 + side] || was[6 + side] != now[6 + side]) && target >= 0 &&
      (moves || std::max(levelWas, levelNow) > target))
    {
      parts |= 1u | (2u << ((side + 1) % 4)) | (2u << ((side + 3) % 4));
    }
  }
  return parts;
}

} // namespace gmm
