#include "BudgetSelection.h"

#include "Levels.h"
#include "SelectLevels.h"
#include "Tessellate.h"
#include "TriangleCount.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace gmm
{

namespace
{

// Phase 1's upper bound here is the coarsest selection's tau (which a block next to the eye
// can make 1e8 px or more); the constants are in BudgetSelection.h.

using Entry = BudgetScratch::Entry;

// Largest error first; ties by block so that a frame's selection does not depend on the
// heap's history.
bool lowerPriority(const Entry& a, const Entry& b)
{
  return a.error < b.error || (a.error == b.error && a.block > b.block);
}

// The table marks levels a block may not take (invalid shape, nodata) with +inf.
bool allowed(const ErrorTable& t, int b, int m)
{
  return t.own(b, m) != std::numeric_limits<float>::infinity();
}

int coarsestAllowed(const Quadtree& qt, const ErrorTable& t, int b)
{
  for (int m = qt.blockTopLevel(b); m > 0; --m)
  {
    if (allowed(t, b, m))
    {
      return m;
    }
  }
  return 0;
}

// The next level below m (> 0) the block may take; level 0 always may.
int nextFiner(const ErrorTable& t, int b, int m)
{
  for (int l = m - 1; l > 0; --l)
  {
    if (allowed(t, b, l))
    {
      return l;
    }
  }
  return 0;
}

double projectedError(const Quadtree& qt, const ErrorTable& t, const std::vector<int8_t>& levels,
  const std::vector<double>& factor, int b)
{
  const double e = blockCertifiedError(qt, t, levels, b);
  return e > 0.0 ? e * factor[b] : 0.0; // 0 * inf would be NaN
}

// The refinement that lowers block b's certified error most: b itself when its own error
// is the largest part; when a strip is, whichever of b and the neighbour across it leaves
// b with the smaller error (strip errors are monotone in the edge level but not in the
// inner level, so refining b can be what the strip needs). Returns the block to refine.
int blockToRefine(const Quadtree& qt, const ErrorTable& t, std::vector<int8_t>& levels, int b)
{
  const int m = levels[b];
  if (!qt.blockIsRingAt(b, m))
  {
    return b; // no strips: only its own error
  }
  const BlockConfig cfg = blockConfigOf(qt, levels, b);
  const std::array<int, 4> nb = qt.blockNeighbours(b);
  double worst = t.ownExact(b, m);
  int side = -1;
  for (int s = 0; s < 4; ++s)
  {
    if (cfg.edgeLevel[s] > m && t.strip(b, s, m, cfg.edgeLevel[s]) > worst)
    {
      worst = t.strip(b, s, m, cfg.edgeLevel[s]);
      side = s;
    }
  }
  if (side >= 0 && levels[nb[side]] == kCoveredLevel)
  {
    // The edge is a merged node's perimeter: only b's own level can change here.
    return m > 0 ? b : nb[side];
  }
  if (side < 0 || m == 0)
  {
    return side < 0 ? b : nb[side];
  }
  // Try both (levels only, restored) and compare b's certified error afterwards.
  const int n = nb[side];
  const int8_t levelN = levels[n];
  levels[n] = static_cast<int8_t>(nextFiner(t, n, levelN));
  const double viaNeighbour = blockCertifiedError(qt, t, levels, b);
  levels[n] = levelN;
  levels[b] = static_cast<int8_t>(nextFiner(t, b, m));
  const double viaSelf = blockCertifiedError(qt, t, levels, b);
  levels[b] = static_cast<int8_t>(m);
  return viaSelf < viaNeighbour ? b : n;
}

class Refiner
{
public:
  Refiner(const Quadtree& qt, const ErrorTable& t, const std::vector<double>& factor,
    std::vector<int8_t>& levels, BudgetScratch& s)
    : qt_(qt)
    , t_(t)
    , factor_(factor)
    , levels_(levels)
    , s_(s)
  {
  }

  std::size_t count(int b) const
  {
    return blockTriangleCount(qt_, b, blockConfigOf(qt_, levels_, b), &t_);
  }

  void push(int b)
  {
    s_.heap.push_back(Entry{ projectedError(qt_, t_, levels_, factor_, b), b, ++s_.stamp[b] });
    std::push_heap(s_.heap.begin(), s_.heap.end(), lowerPriority);
  }

  // Lowers block x to its next level if the selection then still fits `budget`; updates
  // the counts and requeues x and its drawn neighbours (their strips changed).
  bool refine(int x, std::size_t budget, std::size_t& total)
  {
    const std::array<int, 4> nb = qt_.blockNeighbours(x);
    int touched[5] = { x, -1, -1, -1, -1 };
    int n = 1;
    for (int k : nb)
    {
      if (k >= 0 && levels_[k] >= 0)
      {
        touched[n++] = k;
      }
    }
    const int8_t before = levels_[x];
    levels_[x] = static_cast<int8_t>(nextFiner(t_, x, before));
    std::size_t after[5];
    std::size_t removed = 0, added = 0;
    for (int k = 0; k < n; ++k)
    {
      removed += s_.count[touched[k]];
      after[k] = count(touched[k]);
      added += after[k];
    }
    const std::size_t next = total - removed + added;
    if (next > budget)
    {
      levels_[x] = before;
      return false;
    }
    total = next;
    for (int k = 0; k < n; ++k)
    {
      s_.count[touched[k]] = after[k];
      push(touched[k]);
    }
    return true;
  }

private:
  const Quadtree& qt_;
  const ErrorTable& t_;
  const std::vector<double>& factor_;
  std::vector<int8_t>& levels_;
  BudgetScratch& s_;
};


// Phase 1: the finest tau-driven selection (selectLevels) within the budget, by bisection
// of tau in log space between `lo` and `hi` (whose selection, every block at its coarsest
// level, fits). Leaves it in `levels`.
// Returns the number of selections it ran.
int bestTauSelection(const Quadtree& qt, const ErrorTable& table, const std::vector<int>& visible,
  const std::vector<double>& factor, double lo, double hi, std::size_t budget,
  std::vector<int8_t>& levels, BudgetScratch& s)
{
  int trials = 1;
  selectLevels(qt, table, visible, factor, lo, s.trial, s.select);
  if (selectionTriangles(qt, table, visible, s.trial, nullptr) <= budget)
  {
    levels.swap(s.trial);
    return trials;
  }
  for (int k = 0; k < kBudgetBisections && hi > lo * (1.0 + kBudgetTauPrecision); ++k)
  {
    const double mid = std::sqrt(lo * hi);
    ++trials;
    selectLevels(qt, table, visible, factor, mid, s.trial, s.select);
    if (selectionTriangles(qt, table, visible, s.trial, nullptr) <= budget)
    {
      hi = mid;
      levels.swap(s.trial); // the finest fitting selection so far
    }
    else
    {
      lo = mid;
    }
  }
  return trials;
}

} // namespace

std::size_t selectionTriangles(const Quadtree& qt, const ErrorTable& table,
  const std::vector<int>& visible, const std::vector<int8_t>& levels, std::vector<std::size_t>* perBlock)
{
  std::size_t total = 0;
  for (int b : visible)
  {
    if (levels[b] >= 0)
    {
      const std::size_t n = blockTriangleCount(qt, b, blockConfigOf(qt, levels, b), &table);
      total += n;
      if (perBlock)
      {
        (*perBlock)[b] = n;
      }
    }
  }
  return total;
}

double selectionScreenError(const Quadtree& qt, const ErrorTable& table,
  const std::vector<int>& drawn, const std::vector<int8_t>& levels, const std::vector<double>& factor)
{
  double e = 0.0;
  for (int b : drawn)
  {
    if (levels[b] >= 0)
    {
      e = std::max(e, projectedError(qt, table, levels, factor, b));
    }
  }
  return e;
}

void selectLevelsWithinBudget(const Quadtree& qt, const ErrorTable& table,
  const std::vector<int>& visible, const std::vector<double>& factor, double tau,
  std::size_t triangleBudget, std::vector<int8_t>& levels, BudgetScratch& scratch,
  BudgetOutcome& outcome)
{
  outcome = BudgetOutcome();
  levels.assign(qt.blockCount(), -1);
  if (scratch.stamp.size() != levels.size())
  {
    scratch.stamp.assign(levels.size(), 0);
    scratch.count.assign(levels.size(), 0);
  }
  // The coarsest selection, and the tau that selectLevels needs to give it: the largest
  // (monotone) own error at the coarsest levels.
  double coarsestTau = 0.0;
  for (int b : visible)
  {
    if (factor[b] > 0.0)
    {
      levels[b] = static_cast<int8_t>(coarsestAllowed(qt, table, b));
      coarsestTau = std::max(coarsestTau, table.own(b, levels[b]) * factor[b]);
    }
  }
  const std::size_t coarsest = selectionTriangles(qt, table, visible, levels, nullptr);
  if (coarsest > triangleBudget)
  {
    outcome.triangles = coarsest;
    outcome.stop = BudgetStop::OverBudget;
    return;
  }
  int trials = 0;
  if (std::isfinite(coarsestTau) && coarsestTau > tau)
  {
    const double lo = std::max(tau, kLowestBudgetTau);
    trials = bestTauSelection(qt, table, visible, factor, lo, coarsestTau, triangleBudget, levels, scratch);
  }

  refineWithinBudget(qt, table, visible, factor, tau, triangleBudget, 0, 0.0, levels, scratch, outcome);
  outcome.trials = trials;
}

void refineWithinBudget(const Quadtree& qt, const ErrorTable& table, const std::vector<int>& drawn,
  const std::vector<double>& factor, double tau, std::size_t triangleBudget,
  std::size_t fixedTriangles, double fixedError, std::vector<int8_t>& levels,
  BudgetScratch& scratch, BudgetOutcome& outcome)
{
  if (scratch.stamp.size() != levels.size())
  {
    scratch.stamp.assign(levels.size(), 0);
    scratch.count.assign(levels.size(), 0);
  }
  // Refine the largest projected error while the budget lasts.
  Refiner refiner(qt, table, factor, levels, scratch);
  std::size_t total = fixedTriangles + selectionTriangles(qt, table, drawn, levels, &scratch.count);
  scratch.heap.clear();
  for (int b : drawn)
  {
    if (levels[b] >= 0)
    {
      refiner.push(b);
    }
  }
  // A refinement can raise the largest error (a finer block meets coarser neighbours), so
  // the best state seen is kept and the refinements after it are undone at the end.
  std::vector<BudgetScratch::Step>& log = scratch.log;
  log.clear();
  double best = std::numeric_limits<double>::infinity();
  std::size_t bestSteps = 0, bestTotal = total;
  std::vector<Entry>& heap = scratch.heap;
  outcome.stop = fixedError > tau ? BudgetStop::Merged : BudgetStop::Tau;
  while (!heap.empty())
  {
    const Entry top = heap.front();
    std::pop_heap(heap.begin(), heap.end(), lowerPriority);
    heap.pop_back();
    if (top.stamp != scratch.stamp[top.block])
    {
      continue; // superseded by a later entry for the same block
    }
    // The current largest error: every block has a fresh entry; the merged nodes' is fixed.
    const double largest = std::max(top.error, fixedError);
    if (largest < best)
    {
      best = largest;
      bestSteps = log.size();
      bestTotal = total;
    }
    if (top.error <= tau || top.error == 0.0)
    {
      outcome.stop = fixedError > tau ? BudgetStop::Merged : BudgetStop::Tau;
      break;
    }
    if (top.error <= fixedError)
    {
      outcome.stop = BudgetStop::Merged; // no block refinement lowers the largest error
      break;
    }
    const int x = blockToRefine(qt, table, levels, top.block);
    if (levels[x] == kCoveredLevel)
    {
      outcome.stop = BudgetStop::Merged; // a strip beside a merged node, at level 0
      break;
    }
    if (levels[x] <= 0)
    {
      // Unreachable: a positive error is a level > 0's own error or a strip to a neighbour
      // at a coarser level, so x has a finer level. Kept so that no table can loop here.
      outcome.stop = BudgetStop::Tau;
      break;
    }
    const int8_t before = levels[x];
    if (!refiner.refine(x, triangleBudget, total))
    {
      outcome.stop = BudgetStop::Budget;
      break;
    }
    log.push_back(BudgetScratch::Step{ x, before });
    ++outcome.refinements;
  }
  while (log.size() > bestSteps)
  {
    levels[log.back().block] = log.back().level;
    log.pop_back();
    --outcome.refinements;
  }
  outcome.triangles = bestTotal;
}

} // namespace gmm
