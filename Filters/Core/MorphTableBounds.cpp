// Geomorphing's part errors bounded from the error table (MorphBounds.h, tablePartBounds):
// what lets a frame skip measuring the parts of blocks whose budget is loose.
#include "MorphBounds.h"

#include <algorithm>
#include <cmath>

namespace gmm
{

unsigned tablePartBounds(const ErrorTable& table, const Quadtree& qt, int block, const BlockConfig& config,
  int target, const std::array<int, 4>& edgeTarget, unsigned parts, double budget, PartErrors& errors)
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
  unsigned fit = 0;
  if ((parts & 1u) && own + ring <= budget)
  {
    errors.inner[0] = own;
    errors.inner[1] = own + ring;
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
    const double edge = edgeTarget[side] >= 0 ? table.strip(block, side, m, edgeTarget[side]) : 0.0;
    if (!std::isfinite(drawn) || !std::isfinite(edge) || drawn + ring + edge > budget)
    {
      continue;
    }
    double* e = errors.side[side];
    e[0] = drawn;
    e[1] = drawn + ring;
    e[2] = drawn + edge;
    e[3] = drawn + ring + edge;
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
