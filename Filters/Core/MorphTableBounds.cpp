// Geomorphing's part errors bounded from the error table (MorphBounds.h, tablePartBounds):
// what lets a frame skip measuring the parts of blocks whose budget is loose.
#include "MorphBounds.h"
#include "MorphMemos.h"

#include "RasterError.h"
#include "Tessellate.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gmm
{

namespace
{
bool powerOfTwo(int n)
{
  return n > 0 && (n & (n - 1)) == 0;
}

// Whether `block` at level m, its vertices moved onto level `target`'s surface, is that
// surface: a power-of-two block (Levels.h, cellAntiDiagonal) going one level up, to a ring
// or, square, to its one quad (whose diagonal is one of the two its 2 x 2 cells' splits
// draw through the centre).
bool nestsInTarget(const Quadtree& qt, int block, int m, int target)
{
  const int w = qt.blockWidth(block), h = qt.blockHeight(block);
  return target == m + 1 && powerOfTwo(w) && powerOfTwo(h) && (qt.blockIsRingAt(block, target) || w == h);
}

} // namespace

unsigned tablePartBounds(const Heightfield& hf, const ErrorTable& table, const Quadtree& qt, int block,
  const BlockConfig& config, int target, const std::array<int, 4>& edgeTarget, unsigned parts, double budget,
  PartErrors& errors, MorphPartScratch& scratch, SidePolylineMemo* polylines)
{
  const int m = config.level;
  if (target <= m || target >= table.levels || qt.blockHasNodata[block])
  {
    return 0;
  }
  for (int side = 0; side < 4; ++side)
  {
    if (qt.sideAtFullResolution(block, side) || config.edgeLevel[side] < m)
    {
      return 0;
    }
  }
  const double own = table.own(block, m);
  // The ring vertices' target is the block's surface at `target` with its border samples
  // where the edges draw them (blockVertexTarget): on a side whose edge is coarser than the
  // target, on its polyline (the target level's strip toward that edge, glided), and moving
  // from there toward the polyline at the edge's target (between that strip and the one
  // toward the edge's target: the surface's distance to a sample is convex in the factor).
  double ring = table.ownExact(block, target);
  for (int side = 0; side < 4; ++side)
  {
    for (const int n : { config.edgeLevel[side], edgeTarget[side] })
    {
      if (n > target && n < table.levels)
      {
        ring = std::max(ring, static_cast<double>(table.strip(block, side, target, n)));
      }
    }
  }
  if (!std::isfinite(own) || !std::isfinite(ring))
  {
    return 0;
  }
  // Where level m nests in the target, a part with all its vertices at their targets is
  // the target's surface, within `ring` (not own + ring).
  const bool nests = nestsInTarget(qt, block, m, target);
  const double innerAtTarget = nests ? ring : own + ring;
  unsigned bounded = 0, fit = 0;
  if (parts & 1u)
  {
    errors.inner[0] = own;
    errors.inner[1] = innerAtTarget;
    std::fill(std::begin(errors.innerAt), std::end(errors.innerAt), roundUpToFloat(innerAtTarget)); // any edges
    errors.innerFrozen = false;
    bounded |= 1u;
    fit |= std::max(own, innerAtTarget) <= budget ? 1u : 0u;
  }
  for (int side = 0; side < 4; ++side)
  {
    const unsigned bit = 2u << side;
    if (!(parts & bit))
    {
      continue;
    }
    const int n = config.edgeLevel[side];
    if (n >= table.levels || edgeTarget[side] >= table.levels || (edgeTarget[side] >= 0 && edgeTarget[side] <= n))
    {
      continue;
    }
    const double drawn = n > m ? table.strip(block, side, m, n) : own;
    // Edge vertices go from their base heights to the polyline at the edge's target: at
    // most that polyline's distance from the side's samples (within the strip table's
    // error at that edge level), plus, on a glided edge, the base polyline's.
    double edge = edgeTarget[side] >= 0 ? table.strip(block, side, m, edgeTarget[side]) : 0.0;
    if (edgeTarget[side] >= 0 && n > m)
    {
      edge += polylines ? polylines->at(hf, qt, block, side, n, scratch.emit)
                        : sidePolylineError(hf, qt, block, side, n, scratch.emit);
    }
    if (!std::isfinite(drawn) || !std::isfinite(edge))
    {
      continue;
    }
    double corners[4] = { drawn, drawn + ring, drawn + edge, drawn + ring + edge };
    if (nests && n == m && (edgeTarget[side] == target || edgeTarget[side] < 0))
    {
      // The strip is a row of the block's own cells. With every vertex at the target
      // (edge vertices onto the side's polyline at `target`) it is the target's surface,
      // within `ring`; moving only the ring vertices leaves it that surface less the edge
      // vertices' moves, each at most p, the polyline's distance from the side's samples.
      const double p = polylines ? polylines->at(hf, qt, block, side, target, scratch.emit)
                                 : sidePolylineError(hf, qt, block, side, target, scratch.emit);
      const double ringOnly = std::min(drawn + ring, ring + p);
      if (edgeTarget[side] == target)
      {
        edge = std::min(edge, p);
        corners[1] = ringOnly;
        corners[2] = drawn + edge;
        corners[3] = ring;
      }
      else
      {
        corners[1] = corners[3] = ringOnly;
      }
    }
    std::copy(corners, corners + 4, errors.side[side]);
    errors.sideFrozen[side] = false;
    bounded |= bit;
    fit |= std::max({ corners[0], corners[1], corners[2], corners[3] }) <= budget ? bit : 0u;
  }
  errors.bounded |= bounded;
  return fit;
}

unsigned boundedPartsOver(const PartErrors& errors, double budget)
{
  unsigned over = 0;
  if ((errors.bounded & 1u) && std::max(errors.inner[0], errors.inner[1]) > budget)
  {
    over |= 1u;
  }
  for (int side = 0; side < 4; ++side)
  {
    const double* e = errors.side[side];
    if ((errors.bounded & (2u << side)) && std::max({ e[0], e[1], e[2], e[3] }) > budget)
    {
      over |= 2u << side;
    }
  }
  return over;
}

} // namespace gmm
