#include "SelectNodes.h"

#include "CoarsePerimeter.h"
#include "FanMorph.h"
#include "Levels.h"
#include "Tessellate.h"

#include <algorithm>
#include <array>

namespace gmm
{

namespace
{

class Walk
{
public:
  Walk(const Quadtree& qt, const ErrorTable& table, const Frustum* frustum,
    const BoxProjector* projector, double tau, NodeSelection& out, NodeScratch& ns, MorphRamp* ramp)
    : qt_(qt)
    , table_(table)
    , frustum_(frustum)
    , projector_(projector)
    , tau_(tau)
    , out_(out)
    , ns_(ns)
    , mergeGate_(ramp && ramp->active() && ramp->mergeOnPath ? ramp : nullptr)
  {
  }

  // Reaches the blocks below `node` that are in view, drawing nodes whole where allowed;
  // new blocks are appended to ns.newBlocks.
  void node(int index, bool inside)
  {
    const QuadtreeNode& n = qt_.nodes[index];
    if (n.allNodata)
    {
      return; // draws nothing at any level
    }
    if (!inside)
    {
      // Inside a node wholly in view, every descendant is: no more plane tests below.
      const Overlap o = frustum_ ? boxVsFrustum(n.box, *frustum_) : Overlap::Inside;
      if (o == Overlap::Outside)
      {
        return;
      }
      inside = o == Overlap::Inside;
    }
    if (n.childCount == 0)
    {
      out_.blocks.push_back(n.block);
      ns_.newBlocks.push_back(n.block);
      return;
    }
    const float e = table_.mergedError[index];
    if (!ns_.split[index] && e < std::numeric_limits<float>::infinity())
    {
      const double f = memoised(n.box, index, ns_.nodeFactor, ns_.nodeStamp);
      const double budget = errorBudget(tau_, f);
      if (mergeGate_ && fanMorphs(table_, index))
      {
        // The fan morph (FanMorph.h): merged at the end of its path, its children gliding
        // onto its fan before.
        if (budget >= fanMergeBudget(qt_, table_, *mergeGate_, tau_, index))
        {
          merge(index, f);
          return;
        }
        const double t = fanMorphFactor(qt_, table_, *mergeGate_, tau_, index, budget);
        if (t > 0.0)
        {
          mergeGate_->premerging.push_back(FanPremerge{ index, t, f, table_.fanChildrenError[index],
            table_.fanMovedError[index] });
        }
      }
      // Merging on geomorphing's path: only once the node's blocks have reached their top
      // level (rampNodeTopBudget), so that the merge does not skip levels, and a node whose
      // fan is not its blocks' surface only within kMergePopPixels (MorphRamp.h).
      else if (e <= budget &&
        (!mergeGate_ ||
          (rampNodeTopBudget(qt_, table_, *mergeGate_, index) <= budget &&
            (e <= errorBudget(kMergePopPixels, f) || mergeNestsInBlocks(qt_, index)))))
      {
        merge(index, f);
        return;
      }
    }
    for (int k = 0; k < n.childCount; ++k)
    {
      node(n.firstChild + k, inside);
    }
  }

  double factorOf(const Box& box) const { return projector_ ? projector_->factor(box) : 1.0; }

  // factorOf(box) for entry k of a memo (NodeScratch, FactorMemo).
  double memoised(const Box& box, int k, std::vector<double>& value, std::vector<uint32_t>& stamp)
  {
    if (!projector_ || ns_.memoView != projector_)
    {
      return factorOf(box);
    }
    if (stamp[k] != ns_.memoStamp)
    {
      value[k] = projector_->factor(box);
      stamp[k] = ns_.memoStamp;
    }
    return value[k];
  }

  void merge(int index, double f)
  {
    const QuadtreeNode& n = qt_.nodes[index];
    ns_.merged[index] = 1;
    ns_.touched.push_back(index);
    out_.merged.push_back(index);
    out_.mergedFactor.push_back(f);
    out_.mergedDepth.push_back(static_cast<int8_t>(perimeterDepth(index, f)));
    // A node the last selection drew whole is covered already (wasMerged is set during
    // selectNodes' first walk only, which reaches no node below one it draws whole).
    if (!ns_.wasMerged[index])
    {
      setCovered(n, kCoveredLevel);
    }
  }

  // The first node drawn whole on the path from the root to block (c, r), looked for down
  // to node `last` (-1: down to the leaf); -1 when there is none.
  int mergedOnPathTo(int c, int r, int last = -1) const
  {
    int at = 0;
    for (;;)
    {
      if (ns_.merged[at])
      {
        return at;
      }
      const QuadtreeNode& n = qt_.nodes[at];
      int next = -1;
      for (int k = 0; k < n.childCount && next < 0 && at != last; ++k)
      {
        const QuadtreeNode& ch = qt_.nodes[n.firstChild + k];
        if (c >= ch.colBegin && c < ch.colEnd && r >= ch.rowBegin && r < ch.rowEnd)
        {
          next = n.firstChild + k;
        }
      }
      if (next < 0)
      {
        return -1;
      }
      at = next;
    }
  }

  // The blocks below `index` back to -1, except below the nodes drawn whole now.
  void uncover(int index)
  {
    if (ns_.merged[index])
    {
      return;
    }
    const QuadtreeNode& n = qt_.nodes[index];
    if (n.childCount == 0)
    {
      out_.levels[n.block] = -1;
      return;
    }
    for (int k = 0; k < n.childCount; ++k)
    {
      uncover(n.firstChild + k);
    }
  }

  // Splits the merged node that covers block b and walks its children.
  void splitCovering(int b)
  {
    const int index = mergedOnPathTo(b % qt_.blockCols, b / qt_.blockCols);
    if (index < 0)
    {
      return; // not covered (already split this round)
    }
    const QuadtreeNode& n = qt_.nodes[index];
    ns_.merged[index] = 0;
    ns_.split[index] = 1;
    setCovered(n, -1);
    for (int k = 0; k < n.childCount; ++k)
    {
      node(n.firstChild + k, false);
    }
  }

private:
  // The perimeter depth of `index` drawn whole (CoarsePerimeter.h): the coarsest within the
  // budget; on geomorphing's path also within kPerimeterPopPixels of the full perimeter, and
  // for a node merged by the fan morph only once its merge's residual is within that too.
  int perimeterDepth(int index, double f) const
  {
    double popBudget = std::numeric_limits<double>::infinity();
    if (mergeGate_)
    {
      popBudget = errorBudget(kPerimeterPopPixels, f);
      if (fanMorphs(table_, index) && table_.fanResidual[index] > popBudget)
      {
        return kFullPerimeter;
      }
    }
    return coarsestPerimeterDepth(qt_, table_, index, errorBudget(tau_, f), popBudget);
  }

  void setCovered(const QuadtreeNode& n, int8_t level)
  {
    for (int r = n.rowBegin; r < n.rowEnd; ++r)
    {
      int8_t* row = out_.levels.data() + static_cast<std::size_t>(r) * qt_.blockCols;
      std::fill(row + n.colBegin, row + n.colEnd, level);
    }
  }

  const Quadtree& qt_;
  const ErrorTable& table_;
  const Frustum* frustum_;
  const BoxProjector* projector_;
  double tau_;
  NodeSelection& out_;
  NodeScratch& ns_;
  MorphRamp* mergeGate_; // the path, when merges wait for it (MorphRamp::mergeOnPath)
};

// Marks block b and its neighbours for the next round's recheck. Both passes of a round
// read only a block's and its neighbours' levels and budgets (and its path, which changes
// with its level), so a block none of whose inputs changed since a pass last looked at it
// is left as it is by that pass: rampBesideFinerNeighbours finds the same factor, and
// fixStrips the same strips within budget.
void markForRecheck(const Quadtree& qt, int b, NodeScratch& ns)
{
  const std::array<int, 4> neighbour = qt.blockNeighbours(b);
  for (int m : { b, neighbour[0], neighbour[1], neighbour[2], neighbour[3] })
  {
    if (m >= 0 && !ns.recheck[m])
    {
      ns.recheck[m] = 1;
      ns.marked.push_back(m);
    }
  }
}

// The drawn blocks marked for recheck, in `drawn`'s order (the order a whole round takes
// them in); the marks are cleared.
const std::vector<int>& recheckList(const std::vector<int>& drawn, NodeScratch& ns)
{
  ns.recheckList.clear();
  for (int b : drawn)
  {
    if (ns.recheck[b])
    {
      ns.recheckList.push_back(b);
    }
  }
  for (int m : ns.marked)
  {
    ns.recheck[m] = 0;
  }
  ns.marked.clear();
  return ns.recheckList;
}

} // namespace

void selectNodes(const Quadtree& qt, const ErrorTable& table, const Frustum* frustum,
  const BoxProjector* projector, double tau, NodeSelection& out, NodeScratch& ns,
  SelectionScratch& scratch, MorphRamp* ramp, const std::vector<int>* lastBlocks)
{
  const std::size_t blocks = static_cast<std::size_t>(qt.blockCount());
  ns.wasMerged.resize(qt.nodes.size(), 0);
  ns.lastMerged.clear();
  if (lastBlocks && out.levels.size() == blocks)
  {
    // The last selection's blocks back to -1; its merged nodes' blocks stay covered until
    // the walk below has seen which nodes are still drawn whole.
    for (int b : *lastBlocks)
    {
      out.levels[b] = -1;
    }
    ns.lastMerged.swap(out.merged);
    for (int n : ns.lastMerged)
    {
      ns.wasMerged[n] = 1;
    }
  }
  else
  {
    out.levels.assign(blocks, -1);
  }
  out.blocks.clear();
  out.merged.clear();
  out.mergedFactor.clear();
  out.mergedDepth.clear();
  if (ramp)
  {
    ramp->premerging.clear();
  }
  out.factor.resize(blocks);
  scratch.budget.resize(blocks);
  // Flags are cleared where last frame set them: the walk costs what it visits.
  ns.merged.resize(qt.nodes.size(), 0);
  ns.split.resize(qt.nodes.size(), 0);
  for (int index : ns.touched)
  {
    ns.merged[index] = 0;
    ns.split[index] = 0;
  }
  ns.touched.clear();
  ns.newBlocks.clear();
  ns.recheck.resize(blocks, 0);
  if (ns.memoView)
  {
    ns.nodeFactor.resize(qt.nodes.size());
    ns.nodeStamp.resize(qt.nodes.size(), 0);
    ns.blockFactor.resize(blocks);
    ns.blockStamp.resize(blocks, 0);
  }
  if (qt.nodes.empty())
  {
    return;
  }
  Walk walk(qt, table, frustum, projector, tau, out, ns, ramp);
  walk.node(0, false);
  // The last selection's merged nodes not drawn whole now, nor below one that is: their
  // blocks are not covered any more (blocks the walk reached take their levels below).
  // Their flags are cleared before any split walks a node again. (The path to a node's
  // first block passes through the node.) Most are drawn whole again: only the others
  // look for a node above them (a descent from the root was a fifth of a 16385^2 frame).
  for (int n : ns.lastMerged)
  {
    if (!ns.merged[n] && walk.mergedOnPathTo(qt.nodes[n].colBegin, qt.nodes[n].rowBegin, n) < 0)
    {
      walk.uncover(n);
    }
    ns.wasMerged[n] = 0;
  }
  for (bool firstRound = true;; firstRound = false)
  {
    for (int b : ns.newBlocks)
    {
      out.factor[b] = walk.memoised(qt.blockBox[b], b, ns.blockFactor, ns.blockStamp);
      scratch.budget[b] = errorBudget(tau, out.factor[b]);
      out.levels[b] = static_cast<int8_t>(leafLevel(qt, table, b, scratch.budget[b], ramp));
    }
    // The first round looks at every drawn block; a round after splits only at those whose
    // level or a neighbour's changed since the last one (markForRecheck).
    for (std::size_t k = 0; !firstRound && k < ns.newBlocks.size(); ++k)
    {
      markForRecheck(qt, ns.newBlocks[k], ns);
    }
    const std::vector<int>& round = firstRound ? out.blocks : recheckList(out.blocks, ns);
    ns.newBlocks.clear();
    ns.levelsBefore.resize(out.blocks.size());
    for (std::size_t k = 0; k < out.blocks.size(); ++k)
    {
      ns.levelsBefore[k] = out.levels[out.blocks[k]];
    }
    if (ramp && ramp->active())
    {
      rampBesideFinerNeighbours(qt, table, scratch.budget, round, out.levels, *ramp, projector, tau);
    }
    fixStrips(qt, table, scratch.budget, round, out.levels, scratch);
    if (scratch.splitRequests.empty())
    {
      break;
    }
    for (std::size_t k = 0; k < ns.levelsBefore.size(); ++k)
    {
      if (out.levels[out.blocks[k]] != ns.levelsBefore[k])
      {
        markForRecheck(qt, out.blocks[k], ns);
      }
    }
    // Splitting walks nodes and lists blocks; it leaves the requests alone. The block that
    // asked (a neighbour of the covered block b) is looked at again: when the split node's
    // children are drawn whole again, no new block marks it, and its strip beside them
    // would stay over its budget.
    for (int b : scratch.splitRequests)
    {
      if (out.levels[b] == kCoveredLevel)
      {
        walk.splitCovering(b);
      }
      markForRecheck(qt, b, ns);
    }
  }
  // Nodes split after being merged leave stale entries: keep the ones still merged.
  std::size_t kept = 0;
  for (std::size_t k = 0; k < out.merged.size(); ++k)
  {
    if (ns.merged[out.merged[k]])
    {
      out.merged[kept] = out.merged[k];
      out.mergedFactor[kept] = out.mergedFactor[k];
      out.mergedDepth[kept] = out.mergedDepth[k];
      ++kept;
    }
  }
  out.merged.resize(kept);
  out.mergedFactor.resize(kept);
  out.mergedDepth.resize(kept);
  // A node's children glide onto its fan only when they are at their coarsest, as its
  // tables assume: a split or a strip's refinement may have changed them since the walk.
  if (ramp)
  {
    std::vector<FanPremerge>& premerging = ramp->premerging;
    premerging.erase(std::remove_if(premerging.begin(), premerging.end(),
                       [&](const FanPremerge& p) {
                         return ns.merged[p.node] || !childrenAtCoarsest(qt, out.levels, ns.merged, p.node);
                       }),
      premerging.end());
    // The fan morph's tables are of children drawn with full perimeters: a merged child of
    // a node that glides keeps its full perimeter.
    if (!premerging.empty())
    {
      ns.fullPerimeter.resize(qt.nodes.size(), 0);
      for (const FanPremerge& p : premerging)
      {
        const QuadtreeNode& n = qt.nodes[p.node];
        std::fill(ns.fullPerimeter.begin() + n.firstChild, ns.fullPerimeter.begin() + n.firstChild + n.childCount, 1);
      }
      for (std::size_t k = 0; k < out.merged.size(); ++k)
      {
        if (ns.fullPerimeter[out.merged[k]])
        {
          out.mergedDepth[k] = kFullPerimeter;
        }
      }
      for (const FanPremerge& p : premerging)
      {
        const QuadtreeNode& n = qt.nodes[p.node];
        std::fill(ns.fullPerimeter.begin() + n.firstChild, ns.fullPerimeter.begin() + n.firstChild + n.childCount, 0);
      }
    }
  }
}

} // namespace gmm
