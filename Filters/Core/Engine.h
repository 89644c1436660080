// Engine: the whole LOD pipeline for one heightfield, one frame at a time.
//
//   Engine e;
//   std::string err = e.setHeightfield(hf, 64);   // quadtree + error table (input change only)
//   e.setTerrain(sharedTerrain);                   // or: a Terrain another consumer built
//   const FrameStats& s = e.update(view, 1.0);     // cull, select, tessellate (every frame)
//   draw(e.indices());                             // only if !s.reused
#pragma once

#include "BudgetSelection.h"
#include "ErrorTable.h"
#include "Heightfield.h"
#include "IndexArena.h"
#include "Quadtree.h"
#include "SelectLevels.h"
#include "SelectNodes.h"
#include "Tessellate.h"
#include "Terrain.h"
#include "View.h"

#include <cstdint>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

namespace gmm
{

struct FrameStats
{
  // Blocks drawn (in view and holding a valid sample: a block all nodata is never drawn),
  // and the others.
  int visibleBlocks = 0;
  int culledBlocks = 0;
  std::size_t triangles = 0;
  double maxScreenError = 0.0;   // certified bound, pixels (view mode)
  double maxGeometricError = 0.0; // certified bound, data units (metres x height scale)
  bool reused = false;           // indices identical to the previous frame's, not regenerated
  int blocksRetessellated = 0;   // blocks and merged nodes whose triangles were regenerated
  int mergedNodes = 0;           // quadtree nodes drawn whole (their blocks count as visible)
  // Budgeted frames (update with a triangle budget; all 0 / false otherwise):
  std::size_t triangleBudget = 0; // the budget in force
  bool budgetReached = false;     // the budget, not tau, stopped refinement
  bool overBudget = false;        // the coarsest selection alone exceeds it (drawn anyway)
  // With merged nodes: the tau whose selection phase 1 kept (the next frame's natural start,
  // update's startTau), and the start this frame was given; 0 when none.
  double budgetTau = 0.0;
  double budgetStartTau = 0.0;
  int budgetTrials = 0; // whole selections the search ran (BudgetSelection.h's phase 1)
};

// "" when `scale` is a usable vertical exaggeration (finite and > 0), else the reason: the
// one rule of Engine::setHeightScale and the mapper's and filter's SetHeightScale.
std::string validateHeightScale(double scale);

class Engine
{
public:
  // Builds a terrain for `hf` (buildTerrain) and uses it; "" on success, else the reason
  // (the engine is then empty).
  std::string setHeightfield(Heightfield hf, int maxBlockQuads = kDefaultBlockQuads, int threads = 0);

  // Uses a terrain built elsewhere (shared with other engines; never modified). nullptr
  // empties the engine. Per-frame state starts afresh.
  void setTerrain(std::shared_ptr<const Terrain> terrain);

  // One frame for a camera. Returns the frame's statistics; on a bad view (validateView) or
  // tau, sets lastError() and returns stats with zero triangles. tau is in pixels, finite and
  // >= 0: 0 allows only error-free simplification (planes), a huge tau gives the coarsest
  // levels, and NaN, negative and +inf are refused (+inf is not read as "coarsest"). A view
  // that sees no block (e.g. a far plane short of the terrain) is not an error.
  const FrameStats& update(const View& view, double tau);

  // The same frame within at most `triangleBudget` triangles (BudgetSelection.h): the
  // finest tau-driven selection that fits (with merged nodes when they are on), then
  // refinement of the drawn block with the largest projected error until the budget or tau
  // stops it, so maxScreenError is the smallest certified error the budget allows. 0 = no
  // budget, exactly update(view, tau). If even the coarsest selection exceeds the budget
  // it is drawn and stats().overBudget says so.
  // startTau (> 0; with merged nodes) starts phase 1's search there instead of at the
  // coarsest selection: the previous frame's stats().budgetTau makes a moving view's search
  // about half as long (8 selections against 18 over Rainier). The search then finds the
  // boundary nearest the start, which may differ from the cold search's where the count is
  // not monotone in tau (both fit and are certified); a frame is a function of its
  // arguments, startTau included, so another engine given the same start draws the same
  // triangles.
  const FrameStats& update(const View& view, double tau, std::size_t triangleBudget, double startTau = 0.0);

  // Vertical exaggeration: the drawn surface is z0 + scale * height. Culling, the bound and
  // view-independent errors all see the scaled surface; the tables are not rebuilt (errors
  // scale linearly). Returns "" or, for a scale that is not finite and > 0, the reason (the
  // previous scale is kept).
  std::string setHeightScale(double scale);
  double heightScale() const { return heightScale_; }

  // View-independent mode: every block at the coarsest level within maxError (data units,
  // i.e. of the scaled surface; finite and >= 0, else refused like a bad tau).
  const FrameStats& updateForError(double maxError);

  // Tessellates an explicit level assignment (-1 = not drawn); for tests and tools. A list
  // of the wrong size, or a level that is below -1, above the block's top level or of an
  // invalid shape (Levels.h), is refused: lastError() names the block, nothing is drawn.
  const FrameStats& updateWithLevels(const std::vector<int8_t>& levels);

  // Hierarchical selection (SelectNodes.h): far terrain drawn as merged quadtree nodes
  // instead of one coarsest block per leaf. On by default; off selects block by block.
  // Applies to update and updateForError from the next frame on.
  void setMergedNodes(bool on) { mergedNodes_ = on; }
  bool mergedNodes() const { return mergedNodes_; }
  // The nodes drawn whole in the last frame (indices into quadtree().nodes).
  const std::vector<int>& mergedNodeList() const { return drawnMerged_; }
  // Their perimeter depths, in the same order (CoarsePerimeter.h; kFullPerimeter: every
  // block corner on the border).
  const std::vector<int8_t>& mergedNodeDepths() const { return drawnMergedDepth_; }

  // Geomorphing's level path (MorphRamp.h): a finite range > 1 makes update(view, tau)
  // choose each block's level on a path that changes by at most one level per factor
  // `range` of distance, and report the path's morph factors (morphRamp()) for
  // computeMorph; any other range (<= 1, the default, NaN, +inf) selects the coarsest levels
  // within tau. Budgeted and view-independent frames never follow it.
  void setMorphRange(double range) { ramp_.range = range; }
  double morphRange() const { return ramp_.range; }
  // Merging on the path (SelectNodes.h, MorphRamp::mergeOnPath): while update follows the
  // path, a quadtree node is drawn whole only where its blocks have reached their top level
  // on it, so that merges and splits do not skip levels. Off by default: it holds blocks
  // finer in wide views (Documentation/benchmarks-core.md, session 9).
  void setMergeOnPath(bool on) { ramp_.mergeOnPath = on; }
  bool mergeOnPath() const { return ramp_.mergeOnPath; }
  // The path of the last frame, or null when it did not follow one.
  const MorphRamp* morphRamp() const { return rampCurrent_ ? &ramp_ : nullptr; }

  void setErrorMetric(ErrorMetric m) { metric_ = m; }
  ErrorMetric errorMetric() const { return metric_; }

  // The frame's triangles, block by block in block order (concatenated on first use).
  const std::vector<uint32_t>& indices() const;
  // The same triangles in per-block slots, with the ranges this frame changed: what a
  // renderer mirrors in an index buffer and updates incrementally (IndexArena.h).
  const IndexArena& indexArena() const { return arena_; }
  const std::vector<int8_t>& levels() const { return levels_; }
  // Pixels per unit of stored-height error of each block this frame (0 for blocks not in
  // view; stale after a failed or view-independent update): what computeMorph (Morph.h) needs.
  const std::vector<double>& pixelFactors() const { return factor_; }
  // The blocks drawn this frame (level >= 0), in selection order.
  const std::vector<int>& drawnBlocks() const { return drawnList_; }
  // Per block, the configuration it is drawn with this frame (blockConfigOf; level -1 when
  // not drawn): what computeMorph (Morph.h) would otherwise derive again.
  const std::vector<BlockConfig>& drawnConfigs() const { return drawnConfig_; }
  const FrameStats& stats() const { return stats_; }
  const std::string& lastError() const { return lastError_; }
  const Heightfield& heightfield() const { return terrain_->hf; }
  const Quadtree& quadtree() const { return terrain_->qt; }
  const ErrorTable& errorTable() const { return terrain_->table; }
  const std::shared_ptr<const Terrain>& terrain() const { return terrain_; }
  bool empty() const { return terrain_->qt.blockCount() == 0; }

private:
  // Validates the view and tau; false (levels all -1, lastError() set) when the frame is
  // refused.
  bool validFrame(const View& view, double tau);
  // Block by block: culls and computes every visible block's projection factor.
  void cullAndProject(const View& view);
  // `candidates`: the only blocks that may have a level >= 0 this frame (null: any).
  // `merged`: the nodes drawn whole, with their factors when `factor` is given.
  // `mergedDepth`: their perimeter depths (CoarsePerimeter.h; null: full perimeters).
  const FrameStats& finishFrame(const std::vector<double>* factor,
    const std::vector<int>* candidates = nullptr, const std::vector<int>* merged = nullptr,
    const std::vector<double>* mergedFactor = nullptr, const std::vector<int8_t>* mergedDepth = nullptr);
  // Draws merged node `node`'s slot (drawMergedArea) at this frame's levels.
  void drawNodeSlot(int node, FrameStats& s);
  // Queues for drawing again the merged nodes west and north of `block`, whose connects
  // hold its strips on those sides, when `block`'s slot was drawn again.
  void queueNodesBeside(int block);
  // The merged nodes' part of finishFrame: their slots in the arena and statistics.
  bool finishMergedNodes(const std::vector<int>* merged, const std::vector<double>* mergedFactor,
    const std::vector<int8_t>* mergedDepth, const std::vector<int>* candidates, FrameStats& s);
  // The node drawn whole now (nodeDepth_) that covers `block`, or -1.
  int drawnNodeCovering(int block) const;
  // Flags drawn node `node` (-1: none) for a perimeter recheck, once.
  void flagPerimeterRecheck(int node);
  // Flags for a perimeter recheck (nodeRecheck_) the nodes drawn whole now beside `block`,
  // and those around `node`'s border.
  void markNodesBeside(int block);
  void markNodesAround(int node);
  // The nodes whose coarse perimeters may have changed this frame: those new or at another
  // depth (changedNodes_), and the drawn nodes beside them, beside the nodes no longer
  // drawn whole and beside the blocks whose drawn state changed (`candidates`: the blocks
  // that may be drawn now, null: any).
  void markPerimetersToRecheck(const std::vector<int>* candidates);
  // Whether drawn merged node `node`'s perimeter (at this frame's depths and levels) is not
  // the one its slot was drawn with; records the new one.
  bool perimeterChanged(int node);
  // Budgeted frames with merged nodes: phase 1 of BudgetSelection.h on the hierarchical
  // selection, then refineWithinBudget on its blocks. False (nothing selected) when even
  // the coarsest hierarchical selection is over the budget.
  bool selectHierarchicallyWithinBudget(const View& view, double tau, std::size_t triangleBudget,
    double startTau, BudgetOutcome& outcome);
  // Triangles and largest projected certified error (pixels) of the current hierarchical
  // selection (blocks and merged nodes).
  std::size_t hierarchicalTriangles() const;
  double hierarchicalError() const;
  // The merged nodes' part of hierarchicalTriangles.
  std::size_t mergedNodesTriangles() const;
  mutable std::vector<int8_t> countDepth_; // per node, -1 between calls
  mutable std::vector<GridPoint> countPerimeter_;
  // Hierarchical selection for update (frustum and projector given) or updateForError
  // (both null).
  void selectHierarchically(const Frustum* frustum, const BoxProjector* projector,
    double tau, MorphRamp* ramp = nullptr);

  // Never null: an empty Terrain when there is no heightfield.
  std::shared_ptr<const Terrain> terrain_ = std::make_shared<const Terrain>();
  ErrorMetric metric_ = ErrorMetric::Certified;
  bool mergedNodes_ = true;
  struct HierarchicalSelection
  {
    std::vector<int8_t> levels;
    std::vector<double> factor;
    std::vector<int> blocks, merged;
    std::vector<double> mergedFactor;
    std::vector<int8_t> mergedDepth;
  };
  HierarchicalSelection budgetBest_; // the best fitting selection of a budgeted frame
  MorphRamp ramp_;
  bool rampCurrent_ = false;
  NodeSelection nodeSelection_;
  NodeScratch nodeScratch_;
  std::vector<uint8_t> nodeDrawn_, nodeNow_; // per node: in the arena / merged this frame
  // Per node: drawn into its slot this frame (nodes listed in redrawnNodes_), and the drawn
  // nodes whose connects must be drawn again after the blocks are visited.
  std::vector<uint8_t> nodeRedrawn_;
  std::vector<int> redrawnNodes_, nodesToRedraw_;
  std::vector<int> drawnMerged_;             // nodes drawn whole, last finished frame
  std::vector<int8_t> drawnMergedDepth_;     // their perimeter depths (CoarsePerimeter.h)
  // Per node: the perimeter depth of a node drawn whole now, -1 for the others (what
  // PerimeterContext reads); per drawn node with a coarse perimeter, the points its slot
  // was drawn with, since they change with the neighbours across.
  std::vector<int8_t> nodeDepth_;
  std::unordered_map<int, std::vector<GridPoint>> nodePerimeter_;
  std::vector<uint8_t> nodeRecheck_; // per node: flagged by markPerimetersToRecheck
  std::vector<int> recheckNodes_, changedNodes_;
  std::vector<GridPoint> perimeterScratch_;
  double heightScale_ = 1.0;

  std::vector<uint8_t> visible_;
  std::vector<int> visibleList_;
  SelectionScratch selectScratch_;
  BudgetScratch budgetScratch_;
  std::vector<int> drawnList_, nowDrawn_; // blocks drawn last frame / this frame
  std::vector<double> factor_;
  std::vector<int8_t> levels_;
  // levels_, visibleList_ and nodeSelection_.merged are a hierarchical selection's (a
  // budgeted frame's phase 2 changes only its blocks' levels), so the next one updates
  // levels_ in place (selectNodes' lastBlocks). Every other writer of levels_ clears it.
  bool levelsFromSelection_ = false;
  // Per block, its configuration in the last frame (level -1 = not drawn), and what its
  // slot in the arena was drawn with (drawArea's key), so that a frame regenerates only the
  // slots whose triangles changed.
  std::vector<BlockConfig> drawnConfig_;
  std::vector<DrawnSides> drawnSides_;
  // Per drawn block, the levels its configuration was derived from (levelsAround) and the
  // configuration's certified error (blockCertifiedError), so that a frame derives them
  // again only for blocks whose level or a neighbour's changed.
  std::vector<LevelsAround> drawnAround_;
  std::vector<double> drawnError_;
  IndexArena arena_;
  std::vector<uint32_t> blockScratch_;
  EmitScratch emitScratch_; // drawArea / emitMergedNode buffers, reused frame to frame
  mutable std::vector<uint32_t> indices_;
  mutable std::vector<int> indexSlots_; // indices()' slots, in slot order
  mutable std::vector<uint64_t> slotMarks_; // indices()' bit per slot, all 0 between calls
  mutable bool indicesCurrent_ = true;
  FrameStats stats_;
  std::string lastError_;
};

} // namespace gmm
