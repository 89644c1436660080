#include "Engine.h"

#include "CoarsePerimeter.h"
#include "Levels.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace gmm
{

namespace
{
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
  levelsFromSelection_ = false;
  stats_ = FrameStats();
  drawnConfig_.assign(blocks, notDrawn());
  drawnSides_.assign(blocks, DrawnSides{ notDrawn(), {} });
  drawnAround_.assign(blocks, LevelsAround{});
  drawnError_.assign(blocks, 0.0);
  drawnList_.clear();
  // Slots: blocks first, then quadtree nodes drawn whole (slot blocks + node).
  const int nodes = static_cast<int>(terrain_->qt.nodes.size());
  arena_.reset(blocks + nodes);
  nodeDrawn_.assign(nodes, 0);
  nodeRedrawn_.assign(nodes, 0);
  nodeNow_.assign(nodes, 0);
  nodeDepth_.assign(nodes, -1);
  nodeRecheck_.assign(nodes, 0);
  nodePerimeter_.clear();
  drawnMerged_.clear();
  drawnMergedDepth_.clear();
  nodeScratch_ = NodeScratch();
  ramp_.forgetTerrain(); // its memos are of the old terrain's blocks
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
    ramp_.premerging.clear(); // set by a hierarchical selection only
    ramp = &ramp_;
    rampCurrent_ = true;
  }
  if (mergedNodes_)
  {
    const Terrain& t = *terrain_;
    const glm::dmat4 toWorld = heightfieldToWorld(view, t.hf.z0, heightScale_);
    const Frustum frustum = transformPlanes(frustumOf(view), toWorld);
    const BoxProjector projector(view, toWorld, metric_);
    selectHierarchically(&frustum, &projector, tau, ramp);
    return finishFrame(&factor_, &visibleList_, &nodeSelection_.merged, &nodeSelection_.mergedFactor,
      &nodeSelection_.mergedDepth);
  }
  cullAndProject(view);
  const Terrain& t = *terrain_;
  levelsFromSelection_ = false;
  selectLevels(t.qt, t.table, visibleList_, factor_, tau, levels_, selectScratch_, ramp);
  return finishFrame(&factor_, &visibleList_);
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
    levelsFromSelection_ = false;
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
    levelsFromSelection_ = false;
    return finishFrame(nullptr);
  }
  // The table holds stored-height errors; the bound is in the scaled surface's units.
  if (mergedNodes_)
  {
    selectHierarchically(nullptr, nullptr, maxError / heightScale_);
    return finishFrame(nullptr, &visibleList_, &nodeSelection_.merged, nullptr, &nodeSelection_.mergedDepth);
  }
  levelsFromSelection_ = false;
  selectLevelsForError(terrain_->qt, terrain_->table, maxError / heightScale_, levels_);
  return finishFrame(nullptr);
}

void Engine::selectHierarchically(const Frustum* frustum,
  const BoxProjector* projector, double tau, MorphRamp* ramp)
{
  const Terrain& t = *terrain_;
  // The selection updates the engine's level list in place when it holds the last one
  // (levelsFromSelection_); its other lists are rebuilt, and swapped in.
  nodeSelection_.levels.swap(levels_);
  selectNodes(t.qt, t.table, frustum, projector, tau, nodeSelection_, nodeScratch_, selectScratch_, ramp,
    levelsFromSelection_ ? &visibleList_ : nullptr);
  levelsFromSelection_ = true;
  levels_.swap(nodeSelection_.levels);
  factor_.swap(nodeSelection_.factor);
  visibleList_.swap(nodeSelection_.blocks);
}

const FrameStats& Engine::updateWithLevels(const std::vector<int8_t>& levels)
{
  rampCurrent_ = false;
  lastError_.clear();
  levels_.assign(terrain_->qt.blockCount(), -1);
  levelsFromSelection_ = false;
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

void Engine::drawNodeSlot(int node, FrameStats& s)
{
  const Terrain& t = *terrain_;
  blockScratch_.clear();
  drawMergedArea(t.hf, t.qt, levels_, node, blockScratch_, emitScratch_, &nodeDepth_);
  arena_.assign(t.qt.blockCount() + node, blockScratch_.data(), blockScratch_.size());
  nodeDrawn_[node] = 1;
  nodeRedrawn_[node] = 1;
  redrawnNodes_.push_back(node);
  ++s.blocksRetessellated;
}

void Engine::queueNodesBeside(int block)
{
  // A merged node west or north of the block draws the block's strip on that side in its
  // connects (Tessellate.h): what the block draws changed, so that node's slot is drawn
  // again (once, after every block is visited).
  if (redrawnNodes_.size() == drawnMerged_.size())
  {
    return; // every drawn node is drawn this frame already (a frame from scratch)
  }
  const Quadtree& qt = terrain_->qt;
  const std::array<int, 4> neighbour = qt.blockNeighbours(block);
  for (int side : { West, North })
  {
    const int nb = neighbour[side];
    if (nb >= 0 && levels_[nb] == kCoveredLevel)
    {
      const int n = drawnNodeCovering(nb);
      if (n >= 0 && !nodeRedrawn_[n])
      {
        nodeRedrawn_[n] = 1;
        redrawnNodes_.push_back(n);
        nodesToRedraw_.push_back(n);
      }
    }
  }
}

bool Engine::perimeterChanged(int node)
{
  const Terrain& t = *terrain_;
  const int depth = nodeDepth_[node];
  if (depth >= t.qt.nodes[node].height)
  {
    // Every block corner whatever the neighbours: changed only if it was coarse.
    return nodePerimeter_.erase(node) > 0;
  }
  const PerimeterContext across{ levels_, nodeDepth_ };
  coarsePerimeter(t.qt, node, depth, &across, perimeterScratch_);
  std::vector<GridPoint>& drawn = nodePerimeter_[node];
  const bool same = drawn.size() == perimeterScratch_.size() &&
    std::equal(drawn.begin(), drawn.end(), perimeterScratch_.begin(),
      [](GridPoint a, GridPoint b) { return a.i == b.i && a.j == b.j; });
  if (!same)
  {
    drawn = perimeterScratch_;
  }
  return !same;
}

int Engine::drawnNodeCovering(int block) const
{
  const Quadtree& qt = terrain_->qt;
  return qt.firstNodeOver(block % qt.blockCols, block / qt.blockCols, [this](int n) { return nodeDepth_[n] >= 0; });
}

void Engine::flagPerimeterRecheck(int node)
{
  if (node >= 0 && !nodeRecheck_[node])
  {
    nodeRecheck_[node] = 1;
    recheckNodes_.push_back(node);
  }
}

void Engine::markNodesBeside(int block)
{
  const Quadtree& qt = terrain_->qt;
  for (int nb : qt.blockNeighbours(block))
  {
    if (nb >= 0 && levels_[nb] == kCoveredLevel)
    {
      flagPerimeterRecheck(drawnNodeCovering(nb));
    }
  }
}

void Engine::markNodesAround(int node)
{
  // The blocks across its border, side by side: a run of them under one drawn node is
  // looked up once.
  const Quadtree& qt = terrain_->qt;
  const QuadtreeNode& n = qt.nodes[node];
  int last = -1;
  auto across = [&](int c, int r) {
    if (c < 0 || r < 0 || c >= qt.blockCols || r >= qt.blockRows)
    {
      return;
    }
    const int b = qt.blockIndex(c, r);
    if (levels_[b] != kCoveredLevel)
    {
      return;
    }
    if (last >= 0)
    {
      const QuadtreeNode& seen = qt.nodes[last];
      if (c >= seen.colBegin && c < seen.colEnd && r >= seen.rowBegin && r < seen.rowEnd)
      {
        return;
      }
    }
    last = drawnNodeCovering(b);
    flagPerimeterRecheck(last);
  };
  for (int c = n.colBegin; c < n.colEnd; ++c)
  {
    across(c, n.rowBegin - 1);
  }
  last = -1;
  for (int c = n.colBegin; c < n.colEnd; ++c)
  {
    across(c, n.rowEnd);
  }
  last = -1;
  for (int r = n.rowBegin; r < n.rowEnd; ++r)
  {
    across(n.colBegin - 1, r);
  }
  last = -1;
  for (int r = n.rowBegin; r < n.rowEnd; ++r)
  {
    across(n.colEnd, r);
  }
}

bool Engine::finishMergedNodes(const std::vector<int>* merged, const std::vector<double>* mergedFactor,
  const std::vector<int8_t>* mergedDepth, const std::vector<int>* candidates, FrameStats& s)
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
      nodeDepth_[n] = -1;
      nodePerimeter_.erase(n);
      changed = true;
    }
  }
  // Every drawn node's depth first: a perimeter reads its neighbours' (PerimeterContext).
  // A node new or at another depth changes its neighbours' perimeters as well as its own.
  bool coarse = !nodePerimeter_.empty();
  drawnMergedDepth_.resize(now.size());
  changedNodes_.clear();
  for (std::size_t k = 0; k < now.size(); ++k)
  {
    const int n = now[k];
    drawnMergedDepth_[k] = mergedDepth ? (*mergedDepth)[k] : kFullPerimeter;
    coarse = coarse || drawnMergedDepth_[k] < t.qt.nodes[n].height;
    if (!nodeDrawn_[n] || nodeDepth_[n] != drawnMergedDepth_[k])
    {
      changedNodes_.push_back(n);
    }
    nodeDepth_[n] = drawnMergedDepth_[k];
  }
  if (coarse)
  {
    markPerimetersToRecheck(candidates);
  }
  for (std::size_t k = 0; k < now.size(); ++k)
  {
    const int n = now[k];
    nodeNow_[n] = 0;
    const QuadtreeNode& node = t.qt.nodes[n];
    ++s.mergedNodes;
    s.visibleBlocks += (node.colEnd - node.colBegin) * (node.rowEnd - node.rowBegin);
    const double e = mergedErrorAt(t.qt, t.table, n, drawnMergedDepth_[k]);
    s.maxGeometricError = std::max(s.maxGeometricError, e * heightScale_);
    if (mergedFactor && e > 0.0)
    {
      s.maxScreenError = std::max(s.maxScreenError, e * (*mergedFactor)[k]);
    }
    if ((nodeRecheck_[n] && perimeterChanged(n)) || !nodeDrawn_[n])
    {
      drawNodeSlot(n, s);
      changed = true;
    }
  }
  for (int n : recheckNodes_)
  {
    nodeRecheck_[n] = 0;
  }
  recheckNodes_.clear();
  drawnMerged_ = now;
  return changed;
}

void Engine::markPerimetersToRecheck(const std::vector<int>* candidates)
{
  // A coarse perimeter reads the drawn state of the blocks across it and the depths of the
  // nodes drawn whole there (coarsePerimeter): only the nodes beside a change look again.
  for (int n : changedNodes_)
  {
    flagPerimeterRecheck(n);
    markNodesAround(n);
  }
  for (int n : drawnMerged_)
  {
    if (nodeDepth_[n] < 0)
    {
      markNodesAround(n); // no longer drawn whole
    }
  }
  // Blocks drawn by themselves last frame and not now, or now and not then.
  for (int b : drawnList_)
  {
    if (levels_[b] < 0)
    {
      markNodesBeside(b);
    }
  }
  auto newlyDrawn = [&](int b) {
    if (levels_[b] >= 0 && drawnConfig_[b].level < 0)
    {
      markNodesBeside(b);
    }
  };
  if (candidates)
  {
    for (int b : *candidates)
      newlyDrawn(b);
  }
  else
  {
    for (int b = 0; b < terrain_->qt.blockCount(); ++b)
      newlyDrawn(b);
  }
}

const FrameStats& Engine::finishFrame(const std::vector<double>* factor, const std::vector<int>* candidates,
  const std::vector<int>* merged, const std::vector<double>* mergedFactor, const std::vector<int8_t>* mergedDepth)
{
  const Terrain& t = *terrain_;
  FrameStats s;
  arena_.beginFrame();
  bool changed = finishMergedNodes(merged, mergedFactor, mergedDepth, candidates, s);
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
    BlockConfig cfg = notDrawn();
    DrawnSides sides;
    sides.config = cfg;
    if (levels_[b] >= 0)
    {
      ++s.visibleBlocks;
      // A block whose level and neighbours' levels are those it was drawn with keeps its
      // configuration, its error and its slot (blockConfigOf and drawnSidesOf depend on
      // those five levels alone).
      const LevelsAround around = levelsAround(t.qt, levels_, b);
      const bool unchanged = drawnConfig_[b].level >= 0 && around == drawnAround_[b];
      if (!unchanged)
      {
        cfg = blockConfigOf(t.qt, levels_, b);
        sides = drawnSidesOf(t.qt, levels_, b, cfg);
        drawnAround_[b] = around;
        drawnError_[b] = blockCertifiedError(t.qt, t.table, b, cfg);
      }
      const double e = drawnError_[b]; // stored-height units
      s.maxGeometricError = std::max(s.maxGeometricError, e * heightScale_);
      if (factor && e > 0.0) // e == 0 with an infinite factor would give NaN
      {
        s.maxScreenError = std::max(s.maxScreenError, e * (*factor)[b]);
      }
      if (unchanged)
      {
        return;
      }
    }
    else if (drawnConfig_[b].level < 0)
    {
      return; // not drawn now nor then
    }
    drawnConfig_[b] = cfg;
    if (sides == drawnSides_[b])
    {
      return; // what the slot holds is the same (a west / north edge a neighbour draws)
    }
    changed = true;
    drawnSides_[b] = sides;
    blockScratch_.clear();
    if (cfg.level >= 0)
    {
      drawArea(t.hf, t.qt, b, sides, blockScratch_, emitScratch_);
      ++s.blocksRetessellated;
    }
    arena_.assign(b, blockScratch_.data(), blockScratch_.size());
    queueNodesBeside(b);
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
  for (int n : nodesToRedraw_)
  {
    drawNodeSlot(n, s);
    changed = true;
  }
  nodesToRedraw_.clear();
  for (int n : redrawnNodes_)
  {
    nodeRedrawn_[n] = 0;
  }
  redrawnNodes_.clear();
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
    // Block order, then the merged nodes in node order (slot order): only the drawn slots
    // hold triangles, so only those are visited. They are put in order by a bit per slot
    // (node slots all come after block slots) and one pass over its words, which clears
    // them again: sorting the drawn slots was a third of a from-scratch frame's indices()
    // at 5 000 slots, and grows as n log n where the pass grows with slots / 64.
    const int blocks = terrain_->qt.blockCount();
    slotMarks_.resize((static_cast<std::size_t>(blocks) + terrain_->qt.nodes.size() + 63) / 64, 0);
    auto mark = [this](std::size_t slot) { slotMarks_[slot >> 6] |= uint64_t(1) << (slot & 63); };
    for (int b : drawnList_)
    {
      mark(static_cast<std::size_t>(b));
    }
    for (int n : drawnMerged_)
    {
      mark(static_cast<std::size_t>(blocks) + static_cast<std::size_t>(n));
    }
    indexSlots_.clear();
    for (std::size_t w = 0; w < slotMarks_.size(); ++w)
    {
      for (uint64_t bits = slotMarks_[w]; bits != 0; bits &= bits - 1)
      {
        indexSlots_.push_back(static_cast<int>(w * 64 + static_cast<std::size_t>(__builtin_ctzll(bits))));
      }
      slotMarks_[w] = 0;
    }
    indices_.clear();
    arena_.appendTriangles(indexSlots_, indices_);
    indicesCurrent_ = true;
  }
  return indices_;
}

} // namespace gmm
