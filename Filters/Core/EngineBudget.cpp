// Engine: budgeted frames (update with a triangle budget; BudgetSelection.h), block by block
// or on the hierarchical selection with merged nodes.
#include "Engine.h"

#include "TriangleCount.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gmm
{

const FrameStats& Engine::update(const View& view, double tau, std::size_t triangleBudget)
{
  if (triangleBudget == 0)
  {
    return update(view, tau);
  }
  rampCurrent_ = false;
  if (!validFrame(view, tau))
  {
    finishFrame(nullptr);
    stats_.triangleBudget = triangleBudget;
    return stats_;
  }
  const Terrain& t = *terrain_;
  BudgetOutcome outcome;
  if (mergedNodes_ && selectHierarchicallyWithinBudget(view, tau, triangleBudget, outcome))
  {
    finishFrame(&factor_, &visibleList_, &nodeSelection_.merged, &nodeSelection_.mergedFactor);
  }
  else
  {
    cullAndProject(view);
    selectLevelsWithinBudget(t.qt, t.table, visibleList_, factor_, tau, triangleBudget, levels_,
      budgetScratch_, outcome);
    finishFrame(&factor_, &visibleList_);
  }
  stats_.triangleBudget = triangleBudget;
  stats_.budgetReached = outcome.stop != BudgetStop::Tau;
  stats_.overBudget = outcome.stop == BudgetStop::OverBudget;
  return stats_;
}

namespace
{
// What the merged nodes of a selection hold fixed in a budgeted frame: their fans'
// triangles and their largest projected error (pixels).
struct MergedPart
{
  std::size_t triangles = 0;
  double error = 0.0;
};

MergedPart mergedPart(const Terrain& t, const std::vector<int>& merged,
  const std::vector<double>& mergedFactor)
{
  MergedPart p;
  for (std::size_t k = 0; k < merged.size(); ++k)
  {
    p.triangles += mergedNodeTriangleCount(t.qt, merged[k]);
    const double e = t.table.mergedError[merged[k]];
    if (e > 0.0)
    {
      p.error = std::max(p.error, e * mergedFactor[k]);
    }
  }
  return p;
}
} // namespace

double Engine::hierarchicalError() const
{
  const Terrain& t = *terrain_;
  return std::max(selectionScreenError(t.qt, t.table, visibleList_, levels_, factor_),
    mergedPart(t, nodeSelection_.merged, nodeSelection_.mergedFactor).error);
}

std::size_t Engine::hierarchicalTriangles() const
{
  const Terrain& t = *terrain_;
  return selectionTriangles(t.qt, t.table, visibleList_, levels_) +
    mergedPart(t, nodeSelection_.merged, nodeSelection_.mergedFactor).triangles;
}

bool Engine::selectHierarchicallyWithinBudget(
  const View& view, double tau, std::size_t triangleBudget, BudgetOutcome& outcome)
{
  const Terrain& t = *terrain_;
  const glm::dmat4 toWorld = heightfieldToWorld(view, t.hf.z0, heightScale_);
  const Frustum frustum = transformPlanes(frustumOf(view), toWorld);
  const BoxProjector projector(view, toWorld, metric_);
  const FactorMemo memo(nodeScratch_, &projector); // every trial below is of this view
  auto select = [&](double x) {
    selectHierarchically(&frustum, &projector, x);
    return hierarchicalTriangles();
  };
  // The best selection so far is kept aside (the selection's own vectors are swapped in by
  // every trial).
  HierarchicalSelection& best = budgetBest_;
  auto keep = [&]() {
    best.levels = levels_;
    best.factor = factor_;
    best.blocks = visibleList_;
    best.merged = nodeSelection_.merged;
    best.mergedFactor = nodeSelection_.mergedFactor;
  };
  // Phase 1 (BudgetSelection.h) on the hierarchical selection: the coarsest one (every
  // mergeable node drawn whole, tau clamped to the largest budget), then the finest tau
  // whose selection fits, by bisection in log space.
  const double most = std::numeric_limits<double>::max();
  outcome = BudgetOutcome();
  outcome.coarsestTriangles = select(most);
  if (outcome.coarsestTriangles > triangleBudget)
  {
    // Nodes drawn whole reach outside the view, so a finer hierarchical selection can have
    // fewer triangles than this one; the block-by-block search decides (and says when even
    // one quad per block is over budget).
    return false;
  }
  keep();
  // Merging a node can add triangles (its neighbours' strips split it, its fan has more
  // points than its blocks at their levels, or it reaches outside the view), so the count is
  // not monotone in tau: a bisection alone can end far above a tau that fits. So a sweep
  // halves tau from the coarsest selection's own error (above it nothing changes) down to
  // the lowest, or until the count is twice the budget, keeping the finest that fits; then
  // a bisection between it and the next.
  const double lowest = std::max(tau, kLowestBudgetTau);
  double fit = std::max(hierarchicalError(), lowest), below = -1.0;
  for (double x = fit; x > lowest;)
  {
    x = std::max(0.5 * x, lowest);
    const std::size_t n = select(x);
    if (n <= triangleBudget)
    {
      fit = x;
      below = -1.0;
      keep();
      continue;
    }
    if (below < 0.0)
    {
      below = x; // the first failure under the finest fit so far
    }
    if (n > 2 * triangleBudget)
    {
      break; // far over: the count's dips are smaller than this
    }
  }
  if (below > 0.0)
  {
    double lo = below, hi = fit;
    for (int k = 0; k < kBudgetBisections && hi > lo * (1.0 + kBudgetTauPrecision); ++k)
    {
      const double mid = std::sqrt(lo * hi);
      if (select(mid) <= triangleBudget)
      {
        hi = mid;
        keep();
      }
      else
      {
        lo = mid;
      }
    }
  }
  levels_.swap(best.levels);
  factor_.swap(best.factor);
  visibleList_.swap(best.blocks);
  nodeSelection_.merged.swap(best.merged);
  nodeSelection_.mergedFactor.swap(best.mergedFactor);
  // Phase 2 on its blocks; the merged nodes stay.
  const MergedPart fixed = mergedPart(t, nodeSelection_.merged, nodeSelection_.mergedFactor);
  const std::size_t coarsest = outcome.coarsestTriangles;
  refineWithinBudget(t.qt, t.table, visibleList_, factor_, tau, triangleBudget, fixed.triangles,
    fixed.error, levels_, budgetScratch_, outcome);
  outcome.coarsestTriangles = coarsest;
  return true;
}

} // namespace gmm
