#include "Engine.h"

#include "TriangleCount.h"

#include "Levels.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace gmm
{

namespace
{
bool sameConfig(const BlockConfig& a, const BlockConfig& b)
{
  return a.level == b.level && a.edgeLevel == b.edgeLevel;
}

BlockConfig notDrawn()
{
  BlockConfig c;
  c.level = -1;
  c.edgeLevel = { -1, -1, -1, -1 };
  return c;
}
} // namespace

std::string Engine::setHeightfield(Heightfield hf, int maxBlockQuads, int threads)
{
  std::shared_ptr<const Terrain> t;
  lastError_ = buildTerrain(std::move(hf), maxBlockQuads, threads, t);
  setTerrain(std::move(t));
  return lastError_;
}

void Engine::setTerrain(std::shared_ptr<const Terrain> terrain)
{
  terrain_ = terrain ? std::move(terrain) : std::make_shared<const Terrain>();
  const int blocks = terrain_->qt.blockCount();
  levels_.clear();
  stats_ = FrameStats();
  drawnConfig_.assign(blocks, notDrawn());
  drawnList_.clear();
  // Slots: blocks first, then quadtree nodes drawn whole (slot blocks + node).
  const int nodes = static_cast<int>(terrain_->qt.nodes.size());
  arena_.reset(blocks + nodes);
  nodeDrawn_.assign(nodes, 0);
  nodeNow_.assign(nodes, 0);
  drawnMerged_.clear();
  nodeScratch_ = NodeScratch();
  indices_.clear();
  indicesCurrent_ = true;
}

const FrameStats& Engine::update(const View& view, double tau)
{
  rampCurrent_ = false;
  if (!validFrame(view, tau))
  {
    return finishFrame(nullptr);
  }
  MorphRamp* ramp = nullptr;
  if (ramp_.active())
  {
    ramp_.level.resize(terrain_->qt.blockCount());
    ramp_.factor.resize(terrain_->qt.blockCount());
    ramp_.lambda.resize(terrain_->qt.blockCount());
    ramp = &ramp_;
    rampCurrent_ = true;
  }
  if (mergedNodes_)
  {
    const Terrain& t = *terrain_;
    const glm::dmat4 toWorld = heightfieldToWorld(view, t.hf.z0, heightScale_);
    const Frustum frustum = transformPlanes(frustumOf(view), toWorld);
    const BoxProjector projector(view, toWorld, metric_);
    selectHierarchically(&frustum, [&](const Box& b) { return projector.factor(b); }, tau, ramp);
    return finishFrame(&factor_, &visibleList_, &nodeSelection_.merged, &nodeSelection_.mergedFactor);
  }
  cullAndProject(view);
  const Terrain& t = *terrain_;
  selectLevels(t.qt, t.table, visibleList_, factor_, tau, levels_, selectScratch_, ramp);
  return finishFrame(&factor_, &visibleList_);
}

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

bool Engine::validFrame(const View& view, double tau)
{
  lastError_ = empty() ? "no heightfield" : validateView(view);
  if (lastError_.empty() && !(std::isfinite(tau) && tau >= 0.0))
  {
    std::ostringstream why;
    why << "pixel error " << tau << " must be finite and >= 0";
    lastError_ = why.str();
  }
  if (!lastError_.empty())
  {
    levels_.assign(terrain_->qt.blockCount(), -1);
    return false;
  }
  return true;
}

void Engine::cullAndProject(const View& view)
{
  const Terrain& t = *terrain_;
  const glm::dmat4 toWorld = heightfieldToWorld(view, t.hf.z0, heightScale_);
  cullBlocks(t.qt, transformPlanes(frustumOf(view), toWorld), visible_, visibleList_);
  projectionFactors(t.qt, view, toWorld, visibleList_, metric_, factor_);
}

std::string validateHeightScale(double scale)
{
  if (scale > 0.0 && std::isfinite(scale))
  {
    return std::string();
  }
  std::ostringstream why;
  why << "height scale " << scale << " must be finite and > 0";
  return why.str();
}

std::string Engine::setHeightScale(double scale)
{
  std::string err = validateHeightScale(scale);
  if (err.empty())
  {
    heightScale_ = scale;
  }
  return err;
}

const FrameStats& Engine::updateForError(double maxError)
{
  rampCurrent_ = false;
  lastError_ = empty() ? "no heightfield" : std::string();
  if (lastError_.empty() && !(std::isfinite(maxError) && maxError >= 0.0))
  {
    std::ostringstream why;
    why << "maximum geometric error " << maxError << " must be finite and >= 0";
    lastError_ = why.str();
  }
  if (!lastError_.empty())
  {
    levels_.assign(terrain_->qt.blockCount(), -1);
    return finishFrame(nullptr);
  }
  // The table holds stored-height errors; the bound is in the scaled surface's units.
  if (mergedNodes_)
  {
    selectHierarchically(nullptr, [](const Box&) { return 1.0; }, maxError / heightScale_);
    return finishFrame(nullptr, &visibleList_, &nodeSelection_.merged);
  }
  selectLevelsForError(terrain_->qt, terrain_->table, maxError / heightScale_, levels_);
  return finishFrame(nullptr);
}

double Engine::hierarchicalError() const
{
  const Terrain& t = *terrain_;
  double e = 0.0;
  for (int b : visibleList_)
  {
    const double own = levels_[b] >= 0 ? blockCertifiedError(t.qt, t.table, levels_, b) : 0.0;
    if (own > 0.0)
    {
      e = std::max(e, own * factor_[b]);
    }
  }
  for (std::size_t k = 0; k < nodeSelection_.merged.size(); ++k)
  {
    const double own = t.table.mergedError[nodeSelection_.merged[k]];
    if (own > 0.0)
    {
      e = std::max(e, own * nodeSelection_.mergedFactor[k]);
    }
  }
  return e;
}

std::size_t Engine::hierarchicalTriangles() const
{
  const Terrain& t = *terrain_;
  std::size_t n = 0;
  for (int b : visibleList_)
  {
    if (levels_[b] >= 0)
    {
      n += blockTriangleCount(t.qt, b, blockConfigOf(t.qt, levels_, b));
    }
  }
  for (int node : nodeSelection_.merged)
  {
    n += mergedNodeTriangleCount(t.qt, node);
  }
  return n;
}

bool Engine::selectHierarchicallyWithinBudget(
  const View& view, double tau, std::size_t triangleBudget, BudgetOutcome& outcome)
{
  const Terrain& t = *terrain_;
  const glm::dmat4 toWorld = heightfieldToWorld(view, t.hf.z0, heightScale_);
  const Frustum frustum = transformPlanes(frustumOf(view), toWorld);
  const BoxProjector projector(view, toWorld, metric_);
  const auto factorOf = [&](const Box& b) { return projector.factor(b); };
  auto select = [&](double x) {
    selectHierarchically(&frustum, factorOf, x);
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
  std::size_t fixedTriangles = 0;
  double fixedError = 0.0;
  for (std::size_t k = 0; k < nodeSelection_.merged.size(); ++k)
  {
    const int node = nodeSelection_.merged[k];
    fixedTriangles += mergedNodeTriangleCount(t.qt, node);
    const double e = t.table.mergedError[node];
    if (e > 0.0)
    {
      fixedError = std::max(fixedError, e * nodeSelection_.mergedFactor[k]);
    }
  }
  const std::size_t coarsest = outcome.coarsestTriangles;
  refineWithinBudget(t.qt, t.table, visibleList_, factor_, tau, triangleBudget, fixedTriangles,
    fixedError, levels_, budgetScratch_, outcome);
  outcome.coarsestTriangles = coarsest;
  return true;
}

void Engine::selectHierarchically(const Frustum* frustum,
  const std::function<double(const Box&)>& factorOf, double tau, MorphRamp* ramp)
{
  const Terrain& t = *terrain_;
  selectNodes(t.qt, t.table, frustum, factorOf, tau, nodeSelection_, nodeScratch_, selectScratch_, ramp);
  // The engine's per-block lists take the selection's (swapped: both are rebuilt per frame).
  levels_.swap(nodeSelection_.levels);
  factor_.swap(nodeSelection_.factor);
  visibleList_.swap(nodeSelection_.blocks);
}

const FrameStats& Engine::updateWithLevels(const std::vector<int8_t>& levels)
{
  rampCurrent_ = false;
  lastError_.clear();
  levels_.assign(terrain_->qt.blockCount(), -1);
  if (levels.size() != levels_.size())
  {
    std::ostringstream why;
    why << "level list holds " << levels.size() << " levels for " << levels_.size() << " blocks";
    lastError_ = why.str();
    return finishFrame(nullptr);
  }
  const Quadtree& qt = terrain_->qt;
  for (int b = 0; b < qt.blockCount(); ++b)
  {
    const int m = levels[b];
    const int w = qt.blockWidth(b), h = qt.blockHeight(b);
    if (m < -1 || (m >= 0 && (m > topLevel(w, h) || blockShape(w, h, m) == BlockShape::Invalid)))
    {
      std::ostringstream why;
      why << "level " << m << " is not valid for block " << b << " (" << w << " x " << h
          << " quads; -1 = not drawn, 0.." << topLevel(w, h) << " where the shape allows)";
      lastError_ = why.str();
      levels_.assign(terrain_->qt.blockCount(), -1);
      return finishFrame(nullptr);
    }
  }
  levels_ = levels;
  return finishFrame(nullptr);
}

bool Engine::finishMergedNodes(
  const std::vector<int>* merged, const std::vector<double>* mergedFactor, FrameStats& s)
{
  const Terrain& t = *terrain_;
  const int blocks = t.qt.blockCount();
  bool changed = false;
  static const std::vector<int> none;
  const std::vector<int>& now = merged ? *merged : none;
  for (int n : now)
  {
    nodeNow_[n] = 1;
  }
  for (int n : drawnMerged_)
  {
    if (!nodeNow_[n])
    {
      arena_.assign(blocks + n, nullptr, 0);
      nodeDrawn_[n] = 0;
      changed = true;
    }
  }
  for (std::size_t k = 0; k < now.size(); ++k)
  {
    const int n = now[k];
    nodeNow_[n] = 0;
    const QuadtreeNode& node = t.qt.nodes[n];
    ++s.mergedNodes;
    s.visibleBlocks += (node.colEnd - node.colBegin) * (node.rowEnd - node.rowBegin);
    const double e = t.table.mergedError[n];
    s.maxGeometricError = std::max(s.maxGeometricError, e * heightScale_);
    if (mergedFactor && e > 0.0)
    {
      s.maxScreenError = std::max(s.maxScreenError, e * (*mergedFactor)[k]);
    }
    if (!nodeDrawn_[n])
    {
      blockScratch_.clear();
      emitMergedNode(t.hf, t.qt, n, blockScratch_);
      arena_.assign(blocks + n, blockScratch_.data(), blockScratch_.size());
      nodeDrawn_[n] = 1;
      ++s.blocksRetessellated;
      changed = true;
    }
  }
  drawnMerged_ = now;
  return changed;
}

const FrameStats& Engine::finishFrame(const std::vector<double>* factor, const std::vector<int>* candidates,
  const std::vector<int>* merged, const std::vector<double>* mergedFactor)
{
  const Terrain& t = *terrain_;
  FrameStats s;
  arena_.beginFrame();
  bool changed = finishMergedNodes(merged, mergedFactor, s);
  // Only blocks drawn now or last frame can change: the rest of the DEM costs nothing.
  nowDrawn_.clear();
  if (candidates)
  {
    for (int b : *candidates)
    {
      if (levels_[b] >= 0)
      {
        nowDrawn_.push_back(b);
      }
    }
  }
  else
  {
    for (int b = 0; b < t.qt.blockCount(); ++b)
    {
      if (levels_[b] >= 0)
      {
        nowDrawn_.push_back(b);
      }
    }
  }
  auto visit = [&](int b) {
    const BlockConfig cfg = levels_[b] >= 0 ? blockConfigOf(t.qt, levels_, b) : notDrawn();
    if (levels_[b] >= 0)
    {
      ++s.visibleBlocks;
      const double e = blockCertifiedError(t.qt, t.table, levels_, b); // stored-height units
      s.maxGeometricError = std::max(s.maxGeometricError, e * heightScale_);
      if (factor && e > 0.0) // e == 0 with an infinite factor would give NaN
      {
        s.maxScreenError = std::max(s.maxScreenError, e * (*factor)[b]);
      }
    }
    if (sameConfig(cfg, drawnConfig_[b]))
    {
      return;
    }
    changed = true;
    drawnConfig_[b] = cfg;
    blockScratch_.clear();
    if (cfg.level >= 0)
    {
      emitBlock(t.hf, t.qt, b, cfg, BlockPart::Whole, blockScratch_);
      ++s.blocksRetessellated;
    }
    arena_.assign(b, blockScratch_.data(), blockScratch_.size());
  };
  for (int b : nowDrawn_)
  {
    visit(b);
  }
  for (int b : drawnList_)
  {
    if (levels_[b] < 0)
    {
      visit(b); // no longer drawn: its slot is released
    }
  }
  drawnList_.swap(nowDrawn_);
  s.culledBlocks = t.qt.blockCount() - s.visibleBlocks;
  arena_.endFrame();
  if (changed)
  {
    indicesCurrent_ = false; // indices() concatenates on demand; the mapper draws the arena
  }
  s.reused = !changed;
  s.triangles = arena_.liveIndices() / 3;
  stats_ = s;
  return stats_;
}

} // namespace gmm

namespace gmm
{

const std::vector<uint32_t>& Engine::indices() const
{
  if (!indicesCurrent_)
  {
    indices_.clear();
    arena_.appendTriangles(indices_);
    indicesCurrent_ = true;
  }
  return indices_;
}

} // namespace gmm
