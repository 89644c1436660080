// Hierarchical selection: culling and level choice in one walk down the quadtree, which
// draws a node whole (a merged node, Tessellate.h) where its exact error projects within
// the budget, and only descends where it does not. Far terrain then costs a few fans
// instead of one coarsest block per leaf, in triangles and in per-frame work.
//
// The blocks the walk reaches are chosen as selectLevels does (coarsest level within the
// budget, or geomorphing's path when `ramp` is active, then fixStrips). With the path's
// mergeOnPath set, a node is drawn whole only where its blocks would all be at their top
// level on the path (rampNodeTopBudget, MorphRamp.h): merging is then the path's last step
// instead of a jump over several levels; a node that merges by the fan morph (FanMorph.h)
// merges at the end of its own path, its children gliding onto its fan before (listed in
// the ramp's `premerging` once the levels are final and its children at their coarsest).
// Each node drawn whole takes the coarsest perimeter depth its tables allow (CoarsePerimeter.h).
// A block beside a merged node draws that side with its corners only; when that strip does
// not fit the block's budget, the merged node is split (its children are walked in turn)
// and the blocks are re-checked, until every drawn block and every merged node fits. Each
// split goes one level down the quadtree, so this ends. A re-check takes only the blocks
// whose level or a neighbour's changed since the last check (the new blocks, and those the
// last round changed): the others' inputs are those they were last found fitting with.
#pragma once

#include "ErrorTable.h"
#include "Quadtree.h"
#include "SelectLevels.h"
#include "View.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace gmm
{

// Buffers the walk reuses from frame to frame (per engine).
struct NodeScratch
{
  std::vector<uint8_t> merged;   // per node: drawn whole this frame
  std::vector<uint8_t> split;    // per node: may not be drawn whole this frame
  std::vector<int> touched;      // nodes whose flags are set (cleared next frame)
  std::vector<int> newBlocks;    // blocks reached by the last walk
  // An update of the last selection's level list (selectNodes' `lastBlocks`): the nodes it
  // drew whole, flagged in `wasMerged` while the selection runs.
  std::vector<int> lastMerged;
  std::vector<uint8_t> wasMerged;
  // The projector's factors of node and block boxes, kept for one view while `memoView` is
  // that projector (FactorMemo): a budgeted frame runs one whole selection per trial tau,
  // and recomputing the factors was 17 % of its time over Rainier. An entry is current
  // where its stamp is `memoStamp`.
  const BoxProjector* memoView = nullptr;
  uint32_t memoStamp = 0;
  std::vector<double> nodeFactor, blockFactor;
  std::vector<uint32_t> nodeStamp, blockStamp;
  // Rounds after splits: the drawn blocks' levels before a round, and per block whether its
  // level or a neighbour's changed since the last round looked at it (the marked blocks
  // listed, to clear the marks; all clear between selections).
  std::vector<int8_t> levelsBefore;
  std::vector<uint8_t> recheck;
  std::vector<int> marked;
  std::vector<int> recheckList;
  std::vector<uint8_t> fullPerimeter; // per node: a child of a node whose corners glide (0 between frames)
};

// While it lives, the selections in `scratch` with `projector` reuse the factors they
// computed (one view: the projector must not change in that time); none before or after.
class FactorMemo
{
public:
  FactorMemo(NodeScratch& scratch, const BoxProjector* projector)
    : scratch_(scratch)
  {
    scratch_.memoView = projector;
    if (++scratch_.memoStamp == 0)
    {
      // Wrapped around: forget every entry rather than trust one from 2^32 views ago.
      std::fill(scratch_.nodeStamp.begin(), scratch_.nodeStamp.end(), 0u);
      std::fill(scratch_.blockStamp.begin(), scratch_.blockStamp.end(), 0u);
      scratch_.memoStamp = 1;
    }
  }
  ~FactorMemo() { scratch_.memoView = nullptr; }
  FactorMemo(const FactorMemo&) = delete;
  FactorMemo& operator=(const FactorMemo&) = delete;

private:
  NodeScratch& scratch_;
};

// The selection: blocks drawn one by one (levels >= 0, listed in `blocks`), merged nodes
// (`merged`, with their factors in `mergedFactor`), and kCoveredLevel for the blocks below
// those. `frustum` null: everything is in view (view-independent mode). `projector` gives
// each box's pixels per unit of error; null: 1 for every box (view-independent mode, tau
// then a length).
struct NodeSelection
{
  std::vector<int> blocks;
  std::vector<double> factor; // per block (blockCount), for the listed blocks
  std::vector<int8_t> levels; // per block
  std::vector<int> merged;
  std::vector<double> mergedFactor;
  std::vector<int8_t> mergedDepth; // perimeter depths (CoarsePerimeter.h)
};

// `lastBlocks` null: out.levels is written whole (every block). Else out.levels, out.merged
// and *lastBlocks (a list other than out.blocks) must be the last selection's of this
// quadtree, as selectNodes left them (its drawn blocks may have changed levels, not stopped
// being drawn): only the blocks and nodes it drew, and those drawn now, are written, so
// that a frame costs what it draws, not the DEM's block count (a whole list was 14 % of a
// 16385^2 frame).
void selectNodes(const Quadtree& qt, const ErrorTable& table, const Frustum* frustum,
  const BoxProjector* projector, double tau, NodeSelection& out,
  NodeScratch& nodeScratch, SelectionScratch& scratch, MorphRamp* ramp = nullptr,
  const std::vector<int>* lastBlocks = nullptr);

} // namespace gmm
