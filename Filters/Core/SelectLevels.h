// Culling and level selection for one view.
#pragma once

#include "ErrorTable.h"
#include "Heightfield.h"
#include "MorphRamp.h"
#include "Quadtree.h"
#include "View.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace gmm
{

enum class ErrorMetric
{
  // Certified: a vertical displacement of length delta at p (relative to the eye, depth Z)
  // projects to at most f * delta * |v x p| / Z^2 pixels (f = pixels per unit at depth 1,
  // v the unit vertical). Over a box beyond the near plane that is at most
  // f * delta * maxAcross / minDepth, maxAcross the largest |v x p| / Z over the box (at a
  // corner: its level sets are convex cones) and minDepth its smallest depth ("tight");
  // over a box that reaches the near plane, f * delta * maxDist / max(minDepth, near)^2 with
  // maxDist the largest eye distance ("loose", never below the tight one). This also
  // covers the off-axis magnification that delta * f / distance misses.
  Certified,
  // de Boer's approximation: f * delta / (distance from eye to box centre). Cheaper and not
  // a bound; offered for comparison.
  CenterDistance
};

enum class Overlap
{
  Outside,
  Partial,
  Inside
};

// Where a box lies against the frustum (conservative: Partial may be outside).
Overlap boxVsFrustum(const Box& box, const Frustum& fr);

// Calls accept(node) for every node with a valid sample (QuadtreeNode::allNodata) whose box
// the frustum meets and that is wholly inside it or a leaf, descending only through the
// nodes its planes cut (boxVsFrustum), from `node` down: the walk of cullBlocks, so that
// its cost follows the frustum's boundary.
template <class Accept>
void forNodesInFrustum(const Quadtree& qt, int node, const Frustum& fr, Accept&& accept)
{
  const QuadtreeNode& n = qt.nodes[node];
  if (n.allNodata)
  {
    return; // draws nothing: as good as out of view
  }
  const Overlap o = boxVsFrustum(n.box, fr);
  if (o == Overlap::Outside)
  {
    return;
  }
  if (o == Overlap::Inside || n.childCount == 0)
  {
    accept(node);
    return;
  }
  for (int k = 0; k < n.childCount; ++k)
  {
    forNodesInFrustum(qt, n.firstChild + k, fr, accept);
  }
}

// Marks blocks with a valid sample whose box intersects the frustum (1) or not (0), and
// lists those visible ones
// (quadtree order), walking the quadtree with early full-inside accept. The frustum is in
// the quadtree's frame (x, y, stored height): transformPlanes(frustumOf(view),
// heightfieldToWorld(...)). Returns the number of visible blocks. The per-frame steps
// below work on the list, so their cost follows what is in view, not the DEM's size.
int cullBlocks(const Quadtree& qt, const Frustum& frustum, std::vector<uint8_t>& visible,
  std::vector<int>& list);

// Pixels per unit of stored-height error for each listed (visible) block; 0 for the others.
// `toWorld` maps the quadtree's frame to the view's world (heightfieldToWorld): each box's
// corners are taken to world coordinates, where the bound is evaluated, and a vertical
// error of 1 becomes a world displacement of |toWorld * (0, 0, 1, 0)|. Exact for any
// affine toWorld: a non-uniform scale or shear moves both.
void projectionFactors(const Quadtree& qt, const View& view, const glm::dmat4& toWorld,
  const std::vector<int>& visible, ErrorMetric metric, std::vector<double>& factor);

// The factor of projectionFactors for any box of the quadtree's frame (a block's, a
// node's): pixels per unit of stored-height error anywhere inside it, always > 0.
class BoxProjector
{
public:
  BoxProjector(const View& view, const glm::dmat4& toWorld, ErrorMetric metric);
  double factor(const Box& box) const;
  // The certified factor from the box's 8 corners, for any affine toWorld: factor's own
  // path for a toWorld that is not diagonal. For a diagonal one, factor takes the extremes
  // axis by axis instead, which gives the very same double (tests compare the two).
  double cornerFactor(const Box& box) const;

private:
  // The certified factor for a diagonal toWorld, axis by axis; false when it cannot tell
  // (a square out of range). Tight: 4 corner columns (x, y) at the box's lower depth term.
  bool diagonalFactor(const Box& box, double& factor) const;
  View view_;
  glm::dmat4 toWorld_;
  ErrorMetric metric_;
  CameraFrame cam_;
  double ppu_ = 0.0;
  // toWorld's first four columns' x, y, z, the eye and the view direction, as plain
  // doubles for factor's corner loops.
  double column_[4][3] = {};
  double eye_[3] = {};
  double forward_[3] = {};
  double up_[3] = {}; // the unit world direction of a stored-height error
  // toWorld's linear part is diagonal (a DEM's usual frame: spacing, height scale and an
  // offset): each corner term then depends on one box coordinate, and factor takes the
  // extremes axis by axis.
  bool diagonal_ = false;
  // diagonalFactor's per-axis operands, each twice (a lane for the box's lo, one for its
  // hi), aligned for SSE2 loads.
  struct alignas(16) DiagonalLanes
  {
    double scale[3][2], offset[3][2], eye[3][2], forward[3][2];
  } lanes_ = {};
};

// The largest stored-height error that projects within tau pixels at `factor`: tau /
// factor, clamped to a finite value (an infinite budget would accept the +inf of levels
// that are not allowed), 0 for an infinite factor.
// Inline: the quadtree walk asks it for every node it considers drawing whole.
inline double errorBudget(double tau, double factor)
{
  // tau / factor overflows for a huge tau or a tiny factor (a far camera); +inf would let
  // "error <= budget" accept the +inf of levels not allowed (over nodata).
  const double most = std::numeric_limits<double>::max();
  return std::isfinite(factor) ? std::min(tau / factor, most) : 0.0;
}

// Chooses the coarsest level per visible block whose projected error is <= tau pixels, then
// refines neighbours until every side strip joined to a coarser edge is within tau too.
// levels[b] = -1 for culled blocks. tau must be finite and >= 0; any such tau works, DBL_MAX
// included (the per-block budget tau / factor is clamped to a finite value).
// Buffers selectLevels reuses from frame to frame (a caller keeps one per engine), so that a
// frame allocates and clears nothing the size of the DEM.
struct SelectionScratch
{
  std::vector<double> budget;
  std::vector<uint8_t> queued;
  std::vector<int> work;
  // fixStrips: blocks under a merged node (kCoveredLevel) whose edge is too coarse for a
  // neighbour's strip; the node must be split (SelectNodes.h).
  std::vector<int> splitRequests;
};

// Coarsest valid level of block b whose (monotone) own error fits the budget; level 0
// always fits. Budgets are finite (errorBudget), so a level marked +inf never fits.
int coarsestWithin(const ErrorTable& t, int b, int top, double budget);

// The level block b takes before fixStrips: coarsestWithin, or, when `ramp` is active,
// geomorphing's path (MorphRamp.h), recorded in `ramp` (its vectors sized to the blocks).
int leafLevel(const Quadtree& qt, const ErrorTable& t, int b, double budget, MorphRamp* ramp);

// Geomorphing's path beside finer neighbours (MorphRamp.h, rampedLambdaBeside): lowers
// each listed block on its path so that the strips of its finer neighbours stay within their
// budgets as it coarsens, before fixStrips would have to refine it at once. A neighbour
// nearing its refinement (its path's factor toward its next level below 0.5) has its strip
// at its next finer level phased in, so that the refinement does not lower the block at once.
// Only blocks at their path's level are changed, and only to finer levels. With `projector`
// (a camera's frame, and its `tau`), a neighbour out of view (level -1, without nodata)
// counts where its path would put it, its budget taken no smaller than the block's / range:
// so a block does not coarsen at once when its neighbour leaves the view. Without it, such
// neighbours are not looked at.
void rampBesideFinerNeighbours(const Quadtree& qt, const ErrorTable& t,
  const std::vector<double>& budget, const std::vector<int>& drawn, std::vector<int8_t>& levels,
  MorphRamp& ramp, const BoxProjector* projector = nullptr, double tau = 0.0);

// Refines neighbours until every strip of a drawn block (listed in `drawn`) joined to a
// coarser edge fits the block's budget. Levels only decrease, so this ends; a neighbour at
// the block's level (or finer) removes the coarse edge altogether. A neighbour drawn by a
// merged node cannot be refined here: it is listed in scratch.splitRequests instead.
void fixStrips(const Quadtree& qt, const ErrorTable& t, const std::vector<double>& budget,
  const std::vector<int>& drawn, std::vector<int8_t>& levels, SelectionScratch& scratch);

void selectLevels(const Quadtree& qt, const ErrorTable& table, const std::vector<int>& visible,
  const std::vector<double>& factor, double tau, std::vector<int8_t>& levels,
  SelectionScratch& scratch, MorphRamp* ramp = nullptr);

// View-independent selection: every block takes the coarsest level whose error (including
// strips) is <= maxError metres (finite and >= 0).
void selectLevelsForError(
  const Quadtree& qt, const ErrorTable& table, double maxError, std::vector<int8_t>& levels);

// Certified error of a drawn block (metres): its own error at its level, and every strip
// joined to a coarser edge.
double blockCertifiedError(
  const Quadtree& qt, const ErrorTable& table, const std::vector<int8_t>& levels, int block);
// The same for a drawn block whose configuration (blockConfigOf) is known.
double blockCertifiedError(const Quadtree& qt, const ErrorTable& table, int block, const BlockConfig& config);

} // namespace gmm
