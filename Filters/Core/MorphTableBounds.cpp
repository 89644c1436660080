// Geomorphing's part errors bounded from the error table (MorphBounds.h, tablePartBounds):
// what lets a frame skip measuring the parts of blocks whose budget is loose.
#include "MorphBounds.h"

#include "RasterError.h"
#include "Tessellate.h"

#include <algorithm>
#include <cmath>

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

// The largest distance of the samples along `side` of ring `block` at `config` from the
// side's polyline at `level`: how far an edge vertex moves toward that polyline, at most.
// The polyline is the strip's edge line toward an edge at that level (sidePolylines).
double sidePolylineError(const Heightfield& hf, const Quadtree& qt, int block, BlockConfig config, int side,
  int level, EmitScratch& scratch)
{
  config.edgeLevel[side] = level;
  sidePolylines(qt, block, config, side, scratch);
  return polylineError(hf, scratch.outer);
}
} // namespace

unsigned tablePartBounds(const Heightfield& hf, const ErrorTable& table, const Quadtree& qt, int block,
  const BlockConfig& config, int target, const std::array<int, 4>& edgeTarget, unsigned parts, double budget,
  PartErrors& errors, MorphPartScratch& scratch)
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
  const double ring = table.ownExact(block, target);
  if (!std::isfinite(own) || !std::isfinite(ring))
  {
    return 0;
  }
  // Where level m nests in the target, a part with all its vertices at their targets is
  // the target's surface, within `ring` (not own + ring).
  const bool nests = nestsInTarget(qt, block, m, target);
  const double innerAtTarget = nests ? ring : own + ring;
  unsigned fit = 0;
  if ((parts & 1u) && std::max(own, innerAtTarget) <= budget)
  {
    errors.inner[0] = own;
    errors.inner[1] = innerAtTarget;
    errors.innerFrozen = false;
    fit |= 1u;
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
    double edge = edgeTarget[side] >= 0 ? table.strip(block, side, m, edgeTarget[side]) : 0.0;
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
      const double p = sidePolylineError(hf, qt, block, config, side, target, scratch.emit);
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
    if (std::max({ corners[0], corners[1], corners[2], corners[3] }) > budget)
    {
      continue;
    }
    double* e = errors.side[side];
    std::copy(corners, corners + 4, e);
    errors.sideFrozen[side] = false;
    fit |= bit;
  }
  errors.bounded |= fit;
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
