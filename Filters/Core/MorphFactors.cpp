// The factor rules of computeMorph after each block's own factor (MorphFactors.h).
#include "MorphFactors.h"

#include <algorithm>
#include <cmath>

namespace gmm
{

float factorDown(double t)
{
  float f = static_cast<float>(clamp01(t));
  if (static_cast<double>(f) > t)
  {
    f = std::nextafter(f, 0.0f);
  }
  return f;
}

std::array<double, 4> edgeFactors(const std::array<MorphEdge*, 4>& edges)
{
  return { edges[0]->t, edges[1]->t, edges[2]->t, edges[3]->t };
}

double risePixels(const PartErrors& pe, int side, double factor)
{
  double move = 0.0;
  if (side < 0)
  {
    move = pe.inner[1];
    for (const auto& e : pe.side)
    {
      move = std::max({ move, e[1], e[3] });
    }
  }
  else
  {
    move = pe.side[side][0] + pe.side[side][2];
  }
  const double pixels = move * factor;
  return pixels > 0.0 ? kMorphRisePixels / pixels : 1.0;
}

void limitEdgeRises(const std::vector<int8_t>& levels, const std::vector<double>& factor, MorphCache& cache,
  MorphFrame& out)
{
  const std::vector<int>& drawn = out.blocks;
  // Per edge (scratch, entries of this frame's edges only): the factor it may rise to from
  // its setters (-1: no history), and the pixel allowance on top.
  std::vector<std::pair<float, float>>& limit = cache.edgeRise;
  limit.resize(out.vEdges.size() + out.hEdges.size());
  auto limitOf = [&](const MorphEdge* e) -> std::pair<float, float>& {
    const std::size_t v = static_cast<std::size_t>(e - out.vEdges.data());
    return limit[v < out.vEdges.size() ? v : out.vEdges.size() + static_cast<std::size_t>(e - out.hEdges.data())];
  };
  for (std::size_t k = 0; k < drawn.size(); ++k)
  {
    for (const MorphEdge* e : cache.edges[k])
    {
      limitOf(e) = { -1.0f, 1.0f };
    }
  }
  // A side has history when its edge is drawn as in the last frame (level and target).
  auto hasHistory = [&](std::size_t k, int side) {
    const MorphEdge& e = *cache.edges[k][side];
    const MorphEdge& was = cache.slots[cache.drawnSlots[k]].lastEdges[side];
    return e.t > 0.0f && was.level == e.level && was.target == e.target && cache.morphs[k] && factor[drawn[k]] > 0.0;
  };
  for (std::size_t k = 0; k < drawn.size(); ++k)
  {
    const int b = drawn[k];
    const MorphBlockState& state = cache.slots[cache.drawnSlots[k]];
    for (int side = 0; side < 4; ++side)
    {
      if (!hasHistory(k, side))
      {
        continue;
      }
      const MorphEdge& e = *cache.edges[k][side];
      const double setterRise = e.level == levels[b] && state.lastLambda >= 0.0
        ? std::max(0.0, cache.chainAt[k] + static_cast<double>(out.blockT[b]) - state.lastLambda)
        : 0.0;
      std::pair<float, float>& l = limitOf(&e);
      l.first = std::max(l.first, static_cast<float>(state.lastEdges[side].t + setterRise));
      l.second = std::min(l.second, static_cast<float>(risePixels(state.errors, side, factor[b])));
    }
  }
  for (std::size_t k = 0; k < drawn.size(); ++k)
  {
    for (int side = 0; side < 4; ++side)
    {
      MorphEdge& e = *cache.edges[k][side];
      const std::pair<float, float>& l = limitOf(&e);
      if (l.first >= 0.0f && e.t > l.first + l.second)
      {
        e.t = factorDown(static_cast<double>(l.first) + l.second);
      }
    }
  }
}

void fitEdgeFactors(const std::vector<int8_t>& levels, MorphCache& cache, MorphFrame& out)
{
  const std::vector<int>& drawn = out.blocks;
  for (std::size_t k = 0; k < drawn.size(); ++k)
  {
    const int b = drawn[k];
    for (MorphEdge* e : cache.edges[k])
    {
      if (e->target >= 0 && e->level == levels[b])
      {
        e->t = std::max(e->t, out.blockT[b]); // owner factor, lowered below
      }
    }
  }
  for (std::size_t k = 0; k < drawn.size(); ++k)
  {
    const int b = drawn[k];
    const PartErrors& pe = cache.slots[cache.drawnSlots[k]].errors;
    for (int side = 0; side < 4; ++side)
    {
      MorphEdge& e = *cache.edges[k][side];
      if (e.t <= 0.0f)
      {
        continue;
      }
      if (!cache.morphs[k] || pe.sideFrozen[side])
      {
        e.t = 0.0f; // a block that does not morph holds its edges
        continue;
      }
      const double tb = out.blockT[b];
      const double* q = pe.side[side];
      const double at0 = stripBound(q, 0.0, tb), at1 = stripBound(q, 1.0, tb);
      e.t = std::min(e.t, factorDown(linearReach(at0, at1, cache.budgets[k])));
    }
  }
}

namespace
{
// Every drawn edge back to 0 and fitted again (fitEdgeFactors) to the blocks' factors now.
void refitEdgeFactors(const std::vector<int8_t>& levels, MorphCache& cache, MorphFrame& out)
{
  for (const std::array<MorphEdge*, 4>& edges : cache.edges)
  {
    for (MorphEdge* e : edges)
    {
      e->t = 0.0f;
    }
  }
  fitEdgeFactors(levels, cache, out);
}
} // namespace

void yieldToCoarserEdges(const Quadtree& qt, const std::vector<int8_t>& levels, const std::vector<double>& factor,
  MorphCache& cache, MorphFrame& out)
{
  const std::vector<int>& drawn = out.blocks;
  bool yielded = false;
  for (std::size_t k = 0; k < drawn.size(); ++k)
  {
    const int b = drawn[k];
    const MorphBlockState& state = cache.slots[cache.drawnSlots[k]];
    const PartErrors& pe = state.errors;
    if (!cache.morphs[k] || state.lastLambda < 0.0)
    {
      continue;
    }
    const std::array<int, 4> neighbour = qt.blockNeighbours(b);
    const double f = factor[b], budget = cache.budgets[k];
    for (int side = 0; side < 4; ++side)
    {
      const MorphEdge& e = *cache.edges[k][side];
      const MorphEdge& was = state.lastEdges[side];
      if (e.level <= levels[b] || e.target < 0 || neighbour[side] < 0 || pe.sideFrozen[side])
      {
        continue; // not a coarser neighbour's edge
      }
      // The edge's factor that draws it as in the last frame: its own, or 1 where it was
      // drawn at its target level (its setter refined since), the nearest it comes to the
      // last frame's edge however far that had morphed on toward the next level.
      double wasT = 0.0;
      if (was.level == e.level && was.target == e.target)
      {
        wasT = was.t;
      }
      else if (was.level == e.target)
      {
        wasT = 1.0;
      }
      else
      {
        continue;
      }
      const double want = std::min<double>(wasT - risePixels(pe, side, f), out.blockT[neighbour[side]]);
      if (!(want > e.t))
      {
        continue;
      }
      const double* q = pe.side[side];
      const double a0 = stripBound(q, want, 0.0), a1 = stripBound(q, want, 1.0);
      if (!(a0 <= budget))
      {
        continue; // the edge does not fit there even with the block held
      }
      const double tb = out.blockT[b];
      const double reach = std::min(tb, linearReach(a0, a1, budget));
      if ((tb - reach) / risePixels(pe, -1, f) < (want - e.t) / risePixels(pe, side, f))
      {
        out.blockT[b] = factorDown(reach);
        yielded = true;
      }
    }
  }
  if (yielded)
  {
    refitEdgeFactors(levels, cache, out);
  }
}

void fitInnerGridsToEdges(const std::vector<int8_t>& levels, MorphCache& cache, MorphFrame& out)
{
  const std::vector<int>& drawn = out.blocks;
  bool lowered = false;
  for (std::size_t k = 0; k < drawn.size(); ++k)
  {
    const int b = drawn[k];
    const PartErrors& pe = cache.slots[cache.drawnSlots[k]].errors;
    const double tb = out.blockT[b], budget = cache.budgets[k];
    if (!cache.morphs[k] || tb <= 0.0)
    {
      continue;
    }
    // With every edge at its worst (inner[1]) the bound is at least as large: most blocks
    // fit so, without the interpolation.
    const std::array<double, 4> te = edgeFactors(cache.edges[k]);
    if ((1.0 - tb) * pe.inner[0] + tb * pe.inner[1] > budget && innerBound(pe, te, tb) > budget)
    {
      out.blockT[b] = factorDown(std::min(tb, innerReach(pe, te, budget)));
      lowered = true;
    }
  }
  if (!lowered)
  {
    return;
  }
  std::vector<float>& was = cache.edgeWas;
  was.resize(4 * drawn.size());
  for (std::size_t k = 0; k < drawn.size(); ++k)
  {
    for (int side = 0; side < 4; ++side)
    {
      was[4 * k + side] = cache.edges[k][side]->t;
    }
  }
  refitEdgeFactors(levels, cache, out);
  for (std::size_t k = 0; k < drawn.size(); ++k)
  {
    for (int side = 0; side < 4; ++side)
    {
      MorphEdge& e = *cache.edges[k][side];
      e.t = std::min(e.t, was[4 * k + side]);
    }
  }
}

} // namespace gmm
