#include "SelectLevels.h"

#include "Levels.h"
#include "Tessellate.h"

#include <algorithm>
#include <array>
#include <limits>

namespace gmm
{


int coarsestWithin(const ErrorTable& t, int b, int top, double budget)
{
  for (int m = top; m > 0; --m)
  {
    if (t.own(b, m) <= budget)
    {
      return m;
    }
  }
  return 0;
}

int leafLevel(const Quadtree& qt, const ErrorTable& t, int b, double budget, MorphRamp* ramp)
{
  if (!ramp || !ramp->active())
  {
    return coarsestWithin(t, b, qt.blockTopLevel(b), budget);
  }
  MorphChain chain;
  const int links = morphChain(qt, b, chain);
  const double lambda = rampedLambda(t, b, chain, links, budget, *ramp);
  float factor = 0.0f;
  const int m = levelOnChain(chain, links, lambda, factor);
  ramp->lambda[b] = lambda;
  ramp->level[b] = static_cast<int8_t>(m);
  ramp->factor[b] = factor;
  return m;
}

namespace
{
// What rampBesideFinerNeighbours reads of neighbour nb of block b: its level (-1: none to
// look at), budget and place on its path.
struct BesideNeighbour
{
  int level = -1, pathLevel = -1;
  double budget = 0.0;
  float pathFactor = 0.0f;
};

BesideNeighbour besideNeighbour(const Quadtree& qt, const ErrorTable& t, const std::vector<double>& budget,
  const std::vector<int8_t>& levels, MorphRamp& ramp, const BoxProjector* projector, double tau, int b, int nb)
{
  BesideNeighbour n;
  if (nb >= 0 && levels[nb] >= 0)
  {
    n.level = levels[nb];
    n.budget = budget[nb];
    n.pathLevel = ramp.level[nb];
    n.pathFactor = ramp.factor[nb];
  }
  else if (nb >= 0 && levels[nb] == -1 && projector && !qt.blockHasNodata[nb])
  {
    // Out of view, where its path would put it, so that a block does not coarsen at once
    // when its neighbour leaves the view (nor refine at once when it enters). Its budget is
    // taken no smaller than the block's / range (at most one level finer on the path): under
    // the camera a box's factor grows without bound, and the block's hold with it.
    n.budget = std::max(errorBudget(tau, projector->factor(qt.blockBox[nb])), budget[b] / ramp.range);
    MorphChain chain;
    const int links = morphChain(qt, nb, chain);
    n.level = n.pathLevel = levelOnChain(chain, links, rampedLambda(t, nb, chain, links, n.budget, ramp), n.pathFactor);
  }
  return n;
}
} // namespace

void rampBesideFinerNeighbours(const Quadtree& qt, const ErrorTable& t,
  const std::vector<double>& budget, const std::vector<int>& drawn, std::vector<int8_t>& levels,
  MorphRamp& ramp, const BoxProjector* projector, double tau)
{
  for (int b : drawn)
  {
    const int m = levels[b];
    if (m < 0 || m != ramp.level[b])
    {
      continue; // refined below its path already (fixStrips)
    }
    const std::array<int, 4> neighbour = qt.blockNeighbours(b);
    MorphChain chain;
    const int links = morphChain(qt, b, chain);
    double lambda = ramp.lambda[b];
    for (int side = 0; side < 4; ++side)
    {
      const int nb = neighbour[side];
      const BesideNeighbour beside = besideNeighbour(qt, t, budget, levels, ramp, projector, tau, b, nb);
      const int nbLevel = beside.level;
      const double nbBudget = beside.budget;
      if (nbLevel < 0 || !qt.blockIsRingAt(nb, nbLevel) || qt.sideAtFullResolutionAt(b, levels[b], side, nb, nbLevel))
      {
        continue; // no strip of the neighbour joins this edge, or it does not follow b's level
      }
      // The beside path's errors are 0 up to the first link coarser than the neighbour; a
      // floor from that link alone skips most paths (rampPathFloor).
      auto besidePath = [&](int level, double ceiling) {
        const int j = firstLinkAbove(chain, links, level);
        if (j >= links)
        {
          return ceiling; // never coarser than the neighbour: the strip does not change
        }
        const double firstError = t.strip(nb, (side + 2) % 4, level, chain[j]);
        if (j >= 1 && firstError > 0.0 && firstError <= std::numeric_limits<double>::max() &&
          ceiling <= rampPathFloor(j, firstError, nbBudget, ramp.slope()))
        {
          return ceiling;
        }
        return rampedLambdaBeside(t, chain, links, nb, (side + 2) % 4, level, nbBudget, ramp.slope(), ceiling);
      };
      const double atLevel = besidePath(nbLevel, lambda);
      // As the neighbour nears its refinement (its path's factor toward its next level going
      // to 0), its strip at the next finer level takes over, so that the refinement does
      // not lower this block at once.
      const double w = nbLevel == beside.pathLevel ? 1.0 - beside.pathFactor / kBesidePhaseIn : 0.0;
      const int finer = nbLevel - 1;
      lambda = atLevel;
      if (w > 0.0 && finer >= 0 && qt.blockIsRingAt(nb, finer) &&
        !qt.sideAtFullResolutionAt(b, levels[b], side, nb, finer))
      {
        lambda = std::min(atLevel, atLevel - w * (atLevel - besidePath(finer, atLevel)));
      }
    }
    if (lambda < ramp.lambda[b])
    {
      float factor = 0.0f;
      levels[b] = static_cast<int8_t>(levelOnChain(chain, links, lambda, factor));
      ramp.lambda[b] = lambda;
      ramp.level[b] = levels[b];
      ramp.factor[b] = factor;
    }
  }
}

void fixStrips(const Quadtree& qt, const ErrorTable& t, const std::vector<double>& budget,
  const std::vector<int>& drawn, std::vector<int8_t>& levels, SelectionScratch& scratch)
{
  // Every entry of `queued` is back to 0 when the queue empties, so the scratch is only
  // grown, never cleared: a frame touches what it queues, not the whole DEM.
  std::vector<int>& work = scratch.work;
  std::vector<uint8_t>& queued = scratch.queued;
  work.clear();
  scratch.splitRequests.clear();
  if (queued.size() != levels.size())
  {
    queued.assign(levels.size(), 0);
  }
  for (int b : drawn)
  {
    if (levels[b] > 0 || (levels[b] == 0 && qt.blockIsRingAt(b, 0)))
    {
      work.push_back(b);
      queued[b] = 1;
    }
  }
  while (!work.empty())
  {
    const int b = work.back();
    work.pop_back();
    queued[b] = 0;
    const int m = levels[b];
    if (!qt.blockIsRingAt(b, m))
    {
      // Not drawn (blockIsRingAt is false for m < 0), or a one-quad or thin block, whose
      // edges are corner-only: nothing to join.
      continue;
    }
    const std::array<int, 4> neighbour = qt.blockNeighbours(b);
    for (int side = 0; side < 4; ++side)
    {
      const int nb = neighbour[side];
      if (nb < 0)
      {
        continue;
      }
      const int n = edgeLevelOf(qt, levels, b, m, side, nb);
      if (n <= m || t.strip(b, side, m, n) <= budget[b])
      {
        continue;
      }
      if (levels[nb] == kCoveredLevel)
      {
        // The edge is a merged node's: only splitting that node refines it.
        scratch.splitRequests.push_back(nb);
        continue;
      }
      int target = n - 1;
      while (target > m && (t.own(nb, target) == std::numeric_limits<float>::infinity() ||
                             t.strip(b, side, m, target) > budget[b]))
      {
        --target;
      }
      // target == m may be invalid for the neighbour (a smaller block): go finer still.
      while (target > 0 && t.own(nb, target) == std::numeric_limits<float>::infinity())
      {
        --target;
      }
      levels[nb] = static_cast<int8_t>(target);
      if (!queued[nb])
      {
        work.push_back(nb);
        queued[nb] = 1;
      }
    }
  }
}

namespace
{
// `drawn`: the blocks with levels[b] >= 0 (the others are -1).
void selectWithBudgets(const Quadtree& qt, const ErrorTable& table, const std::vector<double>& budget,
  const std::vector<int>& drawn, std::vector<int8_t>& levels, SelectionScratch& scratch,
  MorphRamp* ramp = nullptr)
{
  for (int b : drawn)
  {
    levels[b] = static_cast<int8_t>(leafLevel(qt, table, b, budget[b], ramp));
  }
  if (ramp && ramp->active())
  {
    rampBesideFinerNeighbours(qt, table, budget, drawn, levels, *ramp);
  }
  fixStrips(qt, table, budget, drawn, levels, scratch);
}
} // namespace

void selectLevels(const Quadtree& qt, const ErrorTable& table, const std::vector<int>& visible,
  const std::vector<double>& factor, double tau, std::vector<int8_t>& levels,
  SelectionScratch& scratch, MorphRamp* ramp)
{
  // Budgets are read for drawn (listed) blocks only: the others keep stale values.
  std::vector<double>& budget = scratch.budget;
  budget.resize(static_cast<std::size_t>(qt.blockCount()));
  levels.assign(qt.blockCount(), -1);
  for (int b : visible)
  {
    if (factor[b] > 0.0)
    {
      levels[b] = 0;
      budget[b] = errorBudget(tau, factor[b]);
    }
  }
  selectWithBudgets(qt, table, budget, visible, levels, scratch, ramp);
}

void selectLevelsForError(
  const Quadtree& qt, const ErrorTable& table, double maxError, std::vector<int8_t>& levels)
{
  std::vector<double> budget(qt.blockCount(), maxError);
  levels.assign(qt.blockCount(), -1);
  std::vector<int> all;
  all.reserve(static_cast<std::size_t>(qt.blockCount()));
  for (int b = 0; b < qt.blockCount(); ++b)
  {
    if (!qt.everySampleNodata(b)) // draws nothing at any level: not drawn
    {
      levels[b] = 0;
      all.push_back(b);
    }
  }
  SelectionScratch scratch;
  selectWithBudgets(qt, table, budget, all, levels, scratch);
}

double blockCertifiedError(
  const Quadtree& qt, const ErrorTable& table, const std::vector<int8_t>& levels, int block)
{
  return levels[block] < 0 ? 0.0 : blockCertifiedError(qt, table, block, blockConfigOf(qt, levels, block));
}

double blockCertifiedError(const Quadtree& qt, const ErrorTable& table, int block, const BlockConfig& config)
{
  const int m = config.level;
  double e = table.ownExact(block, m);
  if (qt.blockIsRingAt(block, m))
  {
    for (int side = 0; side < 4; ++side)
    {
      if (config.edgeLevel[side] > m)
      {
        e = std::max(e, static_cast<double>(table.strip(block, side, m, config.edgeLevel[side])));
      }
    }
  }
  return e;
}

} // namespace gmm
