// The fan morph in a frame (FanMorph.h): when a node's children are at their coarsest, how
// far its corners have glided onto its fan, and those corners in the morph frame.
#include "FanMorph.h"

#include "Levels.h"
#include "Tessellate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace gmm
{

namespace
{
constexpr double kInfD = std::numeric_limits<double>::infinity();

// The budget at which child node `child` is at its coarsest: merged by the fan morph, merged
// as merged nodes merge on the path (SelectNodes.h: its blocks at their top level, its fan
// within the budget, and within kMergePopPixels unless it nests), or its blocks at their top
// level when it is not mergeable.
double childCoarsestBudget(const Quadtree& qt, const ErrorTable& table, MorphRamp& ramp, double tau, int child)
{
  if (fanMorphs(table, child))
  {
    return fanMergeBudget(qt, table, ramp, tau, child);
  }
  const double top = rampNodeTopBudget(qt, table, ramp, child);
  if (!mergeableNode(qt, child))
  {
    return top;
  }
  const double e = table.mergedError[child];
  const double gate = mergeNestsInBlocks(qt, child) ? 0.0 : e * tau / kMergePopPixels;
  return std::max({ top, e, gate });
}

// ramp's fan morph memos, started afresh for another quadtree, range or pixel error.
void keepFanMemos(const Quadtree& qt, MorphRamp& ramp, double tau)
{
  if (!(ramp.fanMergeRange == ramp.range) || !(ramp.fanMergeTau == tau) || ramp.fanMerge.size() != qt.nodes.size())
  {
    ramp.fanReady.assign(qt.nodes.size(), std::numeric_limits<double>::quiet_NaN());
    ramp.fanMerge.assign(qt.nodes.size(), std::numeric_limits<double>::quiet_NaN());
    ramp.fanMergeRange = ramp.range;
    ramp.fanMergeTau = tau;
  }
}

// The node's chain: from its ready budget to the largest of that, the moved children's
// error, the fan's and the budget at which its residual projects within kMergePopPixels.
// The one chain fanMergeBudget and fanMorphFactor follow, so that a node merges where its
// factor reaches 1.
std::array<double, 2> fanChain(const Quadtree& qt, const ErrorTable& table, MorphRamp& ramp, double tau, int node)
{
  const double ready = fanReadyBudget(qt, table, ramp, tau, node);
  return { ready, std::max({ ready, static_cast<double>(table.fanMovedError[node]),
                    static_cast<double>(table.mergedError[node]), table.fanResidual[node] * tau / kMergePopPixels }) };
}
} // namespace

double fanReadyBudget(const Quadtree& qt, const ErrorTable& table, MorphRamp& ramp, double tau, int node)
{
  keepFanMemos(qt, ramp, tau);
  if (!std::isnan(ramp.fanReady[node]))
  {
    return ramp.fanReady[node];
  }
  const QuadtreeNode& n = qt.nodes[node];
  double x = 0.0;
  for (int k = 0; k < n.childCount; ++k)
  {
    x = std::max(x, childCoarsestBudget(qt, table, ramp, tau, n.firstChild + k));
  }
  ramp.fanReady[node] = x;
  return x;
}

double fanMergeBudget(const Quadtree& qt, const ErrorTable& table, MorphRamp& ramp, double tau, int node)
{
  keepFanMemos(qt, ramp, tau);
  if (!std::isnan(ramp.fanMerge[node]))
  {
    return ramp.fanMerge[node];
  }
  const std::array<double, 2> chain = fanChain(qt, table, ramp, tau, node);
  // A chain that does not rise still takes the path's range of distance to glide (the
  // corners move however close the errors are): where fanMorphFactor's s ln(budget / ready)
  // reaches 1.
  ramp.fanMerge[node] = !(chain[0] < kInfD) ? kInfD
    : chain[1] > chain[0]                   ? rampTopBudget(chain.data(), 2, ramp.slope())
                                            : chain[0] * std::exp(1.0 / ramp.slope());
  return ramp.fanMerge[node];
}

double fanMorphFactor(const Quadtree& qt, const ErrorTable& table, MorphRamp& ramp, double tau, int node,
  double budget)
{
  const std::array<double, 2> chain = fanChain(qt, table, ramp, tau, node);
  if (!(budget > chain[0]))
  {
    return 0.0;
  }
  if (chain[1] > chain[0])
  {
    return rampPathWithSlope(chain.data(), 2, budget, ramp.slope());
  }
  return chain[0] > 0.0 ? std::min(1.0, ramp.slope() * std::log(budget / chain[0])) : 1.0;
}

bool childrenAtCoarsest(const Quadtree& qt, const std::vector<int8_t>& levels, const std::vector<uint8_t>& merged,
  int node)
{
  // A child out of view draws nothing: whatever its corners do, nothing of it is drawn.
  const QuadtreeNode& n = qt.nodes[node];
  for (int k = 0; k < n.childCount; ++k)
  {
    const int child = n.firstChild + k;
    if (merged[child])
    {
      continue;
    }
    const bool mergeable = mergeableNode(qt, child);
    const QuadtreeNode& q = qt.nodes[child];
    for (int r = q.rowBegin; r < q.rowEnd; ++r)
    {
      for (int c = q.colBegin; c < q.colEnd; ++c)
      {
        const int b = qt.blockIndex(c, r);
        if (levels[b] != -1 && (mergeable || levels[b] != qt.blockTopLevel(b)))
        {
          return false;
        }
      }
    }
  }
  return true;
}

namespace
{
// The fan heights of node's interior block corners (row by row), from `memo` or made there.
const float* fanCornerHeights(const Heightfield& hf, const Quadtree& qt, int node, FanCornerMemo& memo)
{
  if (memo.first.size() != qt.nodes.size())
  {
    memo.reset(qt.nodes.size());
  }
  if (memo.first[node] < 0)
  {
    const QuadtreeNode& n = qt.nodes[node];
    memo.first[node] = static_cast<int32_t>(memo.heights.size());
    for (int r = n.rowBegin + 1; r < n.rowEnd; ++r)
    {
      for (int c = n.colBegin + 1; c < n.colEnd; ++c)
      {
        memo.heights.push_back(static_cast<float>(fanSurfaceHeight(hf, qt, node, qt.colStart[c], qt.rowStart[r])));
      }
    }
  }
  return memo.heights.data() + memo.first[node];
}
} // namespace

void applyFanMorph(const Heightfield& hf, const Quadtree& qt, const std::vector<FanPremerge>& premerging,
  FanCornerMemo& memo, MorphFrame& out)
{
  const std::size_t corners = static_cast<std::size_t>(qt.blockCols + 1) * (qt.blockRows + 1);
  if (out.cornerT.size() != corners)
  {
    out.cornerT.assign(corners, 0.0f);
    out.cornerTarget.assign(corners, 0.0f);
    out.corners.clear();
  }
  for (const FanPremerge& p : premerging)
  {
    if (!(p.t > 0.0))
    {
      continue;
    }
    const QuadtreeNode& n = qt.nodes[p.node];
    const float* fan = fanCornerHeights(hf, qt, p.node, memo);
    for (int r = n.rowBegin + 1; r < n.rowEnd; ++r)
    {
      for (int c = n.colBegin + 1; c < n.colEnd; ++c, ++fan)
      {
        const std::size_t k = static_cast<std::size_t>(r) * (qt.blockCols + 1) + c;
        out.cornerT[k] = static_cast<float>(p.t);
        out.cornerTarget[k] = *fan;
        out.corners.push_back(static_cast<int>(k));
      }
    }
    // The children's drawn heights are affine in t: their error is at most the mix of the
    // children's and the moved children's.
    const double bound = (1.0 - p.t) * p.childrenError + p.t * p.movedError;
    out.maxBoundPixels = std::max(out.maxBoundPixels, p.factor * bound);
  }
}

} // namespace gmm
