// The fan morph (decision record 006): merges of quadtree nodes that do not pop.
//
// A merged node is drawn as one fan (Tessellate.h) whose surface is not its children's, so
// a merge used to replace the children by the fan at once. Here, once a node's children are
// at their coarsest (child nodes drawn whole, blocks at their top level: every vertex then a
// block corner), the block corners strictly inside the node glide vertically onto the fan's
// surface by the node's factor t, as geomorphing moves any vertex; the node merges when t
// reaches 1, and then changes the drawn surface only by the residual: how far the fan is
// from its children with their corners on it (its creases cross their quads). The merge
// waits until that residual projects within kMergePopPixels, so the pop is bounded by the
// table, not estimated.
//
// Tables (per node, ErrorTable::fanResidual, fanMovedError, fanChildrenError): exact, from
// rasterising the fan and the children over every sample of the node; +inf for a node that
// does not morph so (fanMorphable). Selection (SelectNodes.h): the node's factor follows
// geomorphing's path over the chain (its children's readiness R, the end error) with
// R = the budget at which every child is at its coarsest (fanReadyBudget) and the end error
// the largest of R, the moved children's error, the fan's error and the residual's gate, so
// that the drawn children, (1 - t) children + t moved children, stay within the budget.
// The selection lists those nodes in the ramp (MorphRamp::premerging); computeMorph puts
// their corners' factors and fan heights in MorphFrame (cornerT, cornerTarget), which
// morphedHeight and the mapper's vertex shader read.
#pragma once

#include "ErrorTable.h"
#include "Heightfield.h"
#include "Morph.h"
#include "MorphRamp.h"
#include "Quadtree.h"

#include <cstddef>
#include <limits>
#include <vector>

namespace gmm
{

// Whether `node` merges by the fan morph: mergeable, its fan's error exact
// (mergedErrorIsExact), not a 2 x 2 node whose fan is its blocks' surface
// (mergeNestsInBlocks: it merges at once), and no block below it with nodata or a side at
// full resolution (those keep merged nodes' pop gate, SelectNodes.h).
bool fanMorphable(const Quadtree& qt, int node);

// Whether `table` says `node` merges by the fan morph (its residual is finite).
inline bool fanMorphs(const ErrorTable& table, int node)
{
  return static_cast<std::size_t>(node) < table.fanResidual.size() &&
    table.fanResidual[node] < std::numeric_limits<float>::infinity();
}

// The exact errors of a fanMorphable node (heights in stored units, rounded up to float):
// the residual (largest |fan - moved children| over the node's samples), the moved
// children's error and the children's own (largest |surface - sample|), the children drawn
// at their coarsest (mergeable child nodes as fans, other blocks at their top level).
struct FanMorphErrors
{
  float residual, moved, children;
};
// Buffers fanMorphErrors reuses from node to node (a node of 16 x 16 blocks of 32 quads
// needs 2 MB for its fan's heights; allocated afresh, their pages cost a third of the pass).
struct FanMorphScratch
{
  std::vector<double> fan, movedCorner;
  std::vector<GridTriangle> triangles;
};
FanMorphErrors fanMorphErrors(const Heightfield& hf, const Quadtree& qt, int node, FanMorphScratch& scratch);
FanMorphErrors fanMorphErrors(const Heightfield& hf, const Quadtree& qt, int node);

// The height of `node`'s fan surface at sample (i, j) of the node's rectangle (borders
// included): the fan's triangle that holds it, interpolated.
double fanSurfaceHeight(const Heightfield& hf, const Quadtree& qt, int node, int i, int j);

// The smallest error budget at which every child of `node` is at its coarsest on the path
// (`ramp` active, merges on the path) at pixel error `tau`: a fanMorphable child merged
// (fanMergeBudget), a 2 x 2 child that nests merged, other children with their blocks at
// their top level (rampNodeTopBudget). Memoised in `ramp` for its range and tau, as
// fanMergeBudget is.
double fanReadyBudget(const Quadtree& qt, const ErrorTable& table, MorphRamp& ramp, double tau, int node);

// The smallest budget at which fanMorphable `node` merges: where its factor reaches 1.
double fanMergeBudget(const Quadtree& qt, const ErrorTable& table, MorphRamp& ramp, double tau, int node);

// The factor t in [0, 1] of fanMorphable `node` at error budget `budget` (0 below its
// ready budget; 1 from fanMergeBudget on, where it is drawn whole instead).
double fanMorphFactor(const Quadtree& qt, const ErrorTable& table, MorphRamp& ramp, double tau, int node,
  double budget);

// Whether every child of `node` is drawn at its coarsest under the block levels `levels`
// and the nodes drawn whole flagged in `merged` (per node), or not drawn (out of view):
// what the node's tables assume.
bool childrenAtCoarsest(const Quadtree& qt, const std::vector<int8_t>& levels, const std::vector<uint8_t>& merged,
  int node);

// Sets the corners of every listed node (strictly inside it) moving onto its fan by its
// factor in `out` (reset by computeMorph, clearMorph and drawnEdgeFrame), and raises
// out.maxBoundPixels to each node's bound: factor ((1 - t) children's error + t moved
// children's error). The corners' fan heights are kept in `memo` (reset it when the heights
// change). computeMorph calls it with its ramp's list and its cache's memo.
void applyFanMorph(const Heightfield& hf, const Quadtree& qt, const std::vector<FanPremerge>& premerging,
  FanCornerMemo& memo, MorphFrame& out);

} // namespace gmm
