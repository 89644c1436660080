// Engine: budgeted frames (update with a triangle budget; BudgetSelection.h), block by block
// or on the hierarchical selection with merged nodes.
#include "Engine.h"

#include "CoarsePerimeter.h"
#include "TriangleCount.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gmm
{

const FrameStats& Engine::update(const View& view, double tau, std::size_t triangleBudget, double startTau)
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
  int hierarchicalTrials = 0;
  if (mergedNodes_ && selectHierarchicallyWithinBudget(view, tau, triangleBudget, startTau, outcome))
  {
    finishFrame(&factor_, &visibleList_, &nodeSelection_.merged, &nodeSelection_.mergedFactor,
      &nodeSelection_.mergedDepth);
  }
  else
  {
    hierarchicalTrials = outcome.trials; // of a hierarchical search that gave up
    levelsFromSelection_ = false;
    cullAndProject(view);
    selectLevelsWithinBudget(t.qt, t.table, visibleList_, factor_, tau, triangleBudget, levels_,
      budgetScratch_, outcome);
    finishFrame(&factor_, &visibleList_);
  }
  stats_.triangleBudget = triangleBudget;
  stats_.budgetReached = outcome.stop != BudgetStop::Tau;
  stats_.overBudget = outcome.stop == BudgetStop::OverBudget;
  stats_.budgetTau = outcome.tau;
  stats_.budgetTrials = outcome.trials + hierarchicalTrials;
  stats_.budgetStartTau = startTau;
  return stats_;
}

namespace
{
// A tau just below a selection's certified error x: the next finer selection. The step is
// above the rounding of the selection's comparisons (an error against tau / factor) against
// the reported error (error x factor), which a step of one ulp is not.
double justBelow(double x)
{
  return x * (1.0 - 1e-12);
}

// What the merged nodes of a selection hold fixed in a budgeted frame: their fans'
// triangles and their largest projected error (pixels).
struct MergedPart
{
  std::size_t triangles = 0;
  double error = 0.0;
};

// The merged nodes' largest projected error.
double mergedNodesError(const Terrain& t, const NodeSelection& nodes)
{
  double error = 0.0;
  for (std::size_t k = 0; k < nodes.merged.size(); ++k)
  {
    const double e = mergedErrorAt(t.qt, t.table, nodes.merged[k], nodes.mergedDepth[k]);
    if (e > 0.0)
    {
      error = std::max(error, e * nodes.mergedFactor[k]);
    }
  }
  return error;
}
} // namespace

std::size_t Engine::mergedNodesTriangles() const
{
  // A coarse perimeter's points depend on the neighbours across (coarsePerimeter), so those
  // fans are counted from their perimeters at this selection's levels and depths.
  const Terrain& t = *terrain_;
  const NodeSelection& nodes = nodeSelection_;
  std::size_t triangles = 0;
  bool coarse = false;
  for (std::size_t k = 0; k < nodes.merged.size(); ++k)
  {
    if (nodes.mergedDepth[k] < t.qt.nodes[nodes.merged[k]].height)
    {
      coarse = true;
    }
    else
    {
      triangles += mergedNodeTriangleCount(t.qt, nodes.merged[k]);
    }
  }
  if (!coarse)
  {
    return triangles;
  }
  countDepth_.resize(t.qt.nodes.size(), -1);
  for (std::size_t k = 0; k < nodes.merged.size(); ++k)
  {
    countDepth_[nodes.merged[k]] = nodes.mergedDepth[k];
  }
  const PerimeterContext across{ levels_, countDepth_ };
  for (std::size_t k = 0; k < nodes.merged.size(); ++k)
  {
    if (nodes.mergedDepth[k] < t.qt.nodes[nodes.merged[k]].height)
    {
      coarsePerimeter(t.qt, nodes.merged[k], nodes.mergedDepth[k], &across, countPerimeter_);
      triangles += countPerimeter_.size();
    }
  }
  for (int n : nodes.merged)
  {
    countDepth_[n] = -1;
  }
  return triangles;
}

double Engine::hierarchicalError() const
{
  const Terrain& t = *terrain_;
  return std::max(selectionScreenError(t.qt, t.table, visibleList_, levels_, factor_),
    mergedNodesError(t, nodeSelection_));
}

std::size_t Engine::hierarchicalTriangles() const
{
  const Terrain& t = *terrain_;
  return selectionTriangles(t.qt, t.table, visibleList_, levels_) + mergedNodesTriangles();
}

bool Engine::selectHierarchicallyWithinBudget(const View& view, double tau,
  std::size_t triangleBudget, double startTau, BudgetOutcome& outcome)
{
  const Terrain& t = *terrain_;
  const glm::dmat4 toWorld = heightfieldToWorld(view, t.hf.z0, heightScale_);
  const Frustum frustum = transformPlanes(frustumOf(view), toWorld);
  const BoxProjector projector(view, toWorld, metric_);
  const FactorMemo memo(nodeScratch_, &projector); // every trial below is of this view
  int trials = 0;
  auto select = [&](double x) {
    ++trials;
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
    best.mergedDepth = nodeSelection_.mergedDepth;
  };
  // Phase 1 (BudgetSelection.h) on the hierarchical selection: the finest tau whose
  // selection fits, bracketed, then searched to within kBudgetTauPrecision. A trial's
  // selection is the same for every tau between its own certified error and tau (each of
  // its choices compares an error with tau), so a fitting trial moves the upper bound down
  // to its error.
  const double lowest = std::max(tau, kLowestBudgetTau);
  double lo = -1.0, hi = -1.0; // the coarsest failing tau so far, the finest fitting one
  std::size_t loCount = 0, hiCount = 0; // their counts
  double lastError = 0.0; // the last trial's certified error: its selection holds down to it
  double loError = -1.0;  // lo's
  auto trial = [&](double x) {
    const std::size_t n = select(x);
    lastError = hierarchicalError();
    if (n <= triangleBudget)
    {
      keep();
      hi = std::min(x, std::max(lastError, lowest));
      hiCount = n;
    }
    return n;
  };
  auto failed = [&](double x, std::size_t n) { // the last trial, at x, drew n > budget
    lo = x;
    loCount = n;
    loError = lastError;
  };
  auto closed = [&]() { return hi > 0.0 && (hi <= lowest || lo > 0.0); };
  outcome = BudgetOutcome();
  // Warm start: at startTau (the previous frame's tau), then steps away from it that double in
  // log space (kWarmStep, kWarmStep^2, ...) until a bracket closes. A view that moved a
  // little needs two or three trials; one that moved far falls back to the cold start.
  if (startTau > 0.0 && std::isfinite(startTau))
  {
    double x = std::max(startTau, lowest);
    const std::size_t first = trial(x);
    const bool fitted = first <= triangleBudget;
    if (!fitted)
    {
      failed(x, first);
    }
    // After a frame at full resolution the start is kLowestBudgetTau, which says nothing of
    // where this frame's boundary is once that no longer fits: no steps from it.
    const bool fromFullResolution = startTau <= kLowestBudgetTau;
    for (int k = 0; k < kWarmSteps && !closed() && !fromFullResolution; ++k)
    {
      const double step = std::pow(kWarmStep, std::ldexp(1.0, k));
      x = fitted ? std::max(hi / step, lowest) : x * step;
      const std::size_t n = trial(x);
      if (n > triangleBudget)
      {
        failed(x, n);
      }
    }
  }
  const bool cold = !closed();
  bool fullResolution = false;
  if (cold && lowest > startTau)
  {
    // Full resolution when it fits: a sweep would halve tau from the coarsest selection's
    // error all the way down to kLowestBudgetTau (about 25 selections, 37 ms of a frame
    // over Puget Sound) to find it. Every block in view at level 0 bounds what that
    // selection draws, in a walk over the nodes the frustum's planes cut.
    fullResolution = fullResolutionTrianglesInView(t.qt, frustum) <= triangleBudget &&
      trial(lowest) <= triangleBudget;
  }
  if (cold && !fullResolution)
  {
    // Cold start: the coarsest selection (every mergeable node drawn whole, tau clamped to
    // the largest budget), then tau halved from its error (above it nothing changes) down
    // to the lowest, or until the count is twice the budget, keeping the finest that fits.
    // Merging a node can add triangles (its neighbours' strips split it, its fan has more
    // points than its blocks at their levels, or it reaches outside the view), so the count
    // is not monotone in tau: a bisection alone can end far above a tau that fits.
    lo = hi = -1.0;
    const std::size_t coarsest = trial(std::numeric_limits<double>::max());
    // Nodes drawn whole reach outside the view, so when the coarsest selection is over the
    // budget a finer one can still fit: the sweep starts from its error all the same (when
    // finite: nodata's is not), and only if nothing fits does the block-by-block search
    // decide (and say when even one quad per block is over budget).
    const double coarsestError = hierarchicalError();
    if (coarsest > triangleBudget && !(coarsestError <= std::numeric_limits<double>::max()))
    {
      outcome.trials = trials;
      return false;
    }
    for (double x = hi > 0.0 ? hi : std::max(coarsestError, lowest); x > lowest;)
    {
      // Halved, or just below the last selection's error where that is lower: the selection
      // is the same from its error up, so a tau there would repeat it.
      x = std::max(std::min(0.5 * (hi > 0.0 ? std::min(x, hi) : x), justBelow(lastError)), lowest);
      const std::size_t n = trial(x);
      if (n <= triangleBudget)
      {
        lo = -1.0; // a failure above a finer fit no longer bounds it
      }
      else if (lo < 0.0)
      {
        failed(x, n); // the first failure under the finest fit so far
      }
      if (n > 2 * triangleBudget)
      {
        break; // far over: the count's dips are smaller than this
      }
    }
    if (hi < 0.0)
    {
      outcome.trials = trials;
      return false; // nothing fitted
    }
  }
  // Then the crossing, interpolated: the count is close to a power of tau between two
  // trials (linear in log-log), so the next trial is where that line meets the budget;
  // after two trials on the same side, the middle instead (a step of the count, or a dip,
  // would stall the interpolation). The count moves by a few dozen triangles between
  // neighbouring selections, so this ends where bisection would, in fewer trials.
  int sameSide = 0;
  bool lastFitted = false;
  for (int k = 0; k < kBudgetBisections && lo > 0.0 && hi > lo * (1.0 + kBudgetTauPrecision); ++k)
  {
    double share = 0.5;
    const double countLo = std::log(static_cast<double>(loCount));
    const double countHi = std::log(static_cast<double>(std::max<std::size_t>(hiCount, 1)));
    if (sameSide < 2 && countLo > countHi)
    {
      share = std::clamp((countLo - std::log(static_cast<double>(triangleBudget))) / (countLo - countHi),
        kInterpolationMargin, 1.0 - kInterpolationMargin);
    }
    const double x = lo * std::pow(hi / lo, share);
    const std::size_t n = trial(x);
    const bool fitted = n <= triangleBudget;
    if (!fitted)
    {
      failed(x, n);
    }
    sameSide = k > 0 && fitted == lastFitted ? sameSide + 1 : 0;
    lastFitted = fitted;
  }
  // Below the bracket (cold starts): merging makes the count non-monotone in tau, so a
  // failure does not bound the fits below it, and a dip a few per cent deep is narrower
  // than the sweep's halving steps. Walk down from the bracket's failure (or from the finest
  // fit, where its error is lower) through the next finer selections one at a time, each
  // just below the last one's error, while the counts keep finding new lows: the walk stops
  // after kWalkPatience selections without one. A fit on the way is kept (trial).
  std::size_t least = loCount;
  int sinceLeast = 0;
  for (int k = 0; cold && k < kWalkSteps && lo > 0.0 && std::min(hi, loError) > lowest; ++k)
  {
    const double x = std::max(justBelow(std::min(hi, loError)), lowest);
    const std::size_t n = trial(x);
    if (n > triangleBudget)
    {
      loError = lastError;
    }
    if (x <= lowest)
    {
      break; // tau's own selection: nothing finer is asked for
    }
    if (n < least)
    {
      least = n;
      sinceLeast = 0;
    }
    else if (++sinceLeast >= kWalkPatience)
    {
      break; // the count is climbing away from the budget
    }
  }
  levels_.swap(best.levels);
  factor_.swap(best.factor);
  visibleList_.swap(best.blocks);
  nodeSelection_.merged.swap(best.merged);
  nodeSelection_.mergedFactor.swap(best.mergedFactor);
  nodeSelection_.mergedDepth.swap(best.mergedDepth);
  // Phase 2 on its blocks; the merged nodes stay.
  const MergedPart fixed{ mergedNodesTriangles(), mergedNodesError(t, nodeSelection_) };
  refineWithinBudget(t.qt, t.table, visibleList_, factor_, tau, triangleBudget, fixed.triangles,
    fixed.error, levels_, budgetScratch_, outcome);
  outcome.tau = hi;
  outcome.trials = trials;
  return true;
}

} // namespace gmm
