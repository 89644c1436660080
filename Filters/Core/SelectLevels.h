// Level selection for one view: each block's level from its error table and the view's
// budgets, geomorphing's path, and the neighbour fix-up (culling: Culling.h; the
// projection of errors to pixels: ErrorProjection.h).
#pragma once

#include "Culling.h"
#include "ErrorProjection.h"
#include "ErrorTable.h"
#include "Heightfield.h"
#include "MorphRamp.h"
#include "Quadtree.h"
#include "View.h"

#include <cstdint>
#include <vector>

namespace gmm
{

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
