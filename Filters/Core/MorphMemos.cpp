#include "MorphMemos.h"

#include "RasterError.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>

namespace gmm
{

float SidePolylineMemo::at(const Heightfield& hf, const Quadtree& qt, int block, int side, int level,
  EmitScratch& scratch)
{
  const int perSide = qt.blockTopLevels[block] + 1;
  if (level < 0 || level >= perSide)
  {
    return sidePolylineError(hf, qt, block, side, level, scratch);
  }
  if (this->first[block] < 0)
  {
    this->first[block] = static_cast<int32_t>(this->values.size());
    this->values.resize(this->values.size() + 4 * static_cast<std::size_t>(perSide),
      std::numeric_limits<float>::quiet_NaN());
  }
  const std::size_t at = static_cast<std::size_t>(this->first[block]) + static_cast<std::size_t>(side * perSide + level);
  float& v = this->values[at];
  if (std::isnan(v))
  {
    v = sidePolylineError(hf, qt, block, side, level, scratch);
  }
  return v;
}

void SidePolylineMemo::reset(int blocks)
{
  this->first.assign(static_cast<std::size_t>(blocks), -1);
  this->values.clear();
}

bool InnerErrorMemo::hasLevel(const Quadtree& qt, int block, int level) const
{
  // A block at its top level has no target, hence no inner part that morphs.
  return block >= 0 && block < static_cast<int>(this->first.size()) && level >= 0 &&
    level < qt.blockTopLevels[block];
}

InnerEdges innerEdgesOf(const BlockConfig& config, int target, const std::array<int, 4>& edgeTarget)
{
  InnerEdges e;
  for (int side = 0; side < 4; ++side)
  {
    e[side] = static_cast<int8_t>(config.edgeLevel[side] > target ? config.edgeLevel[side] : -1);
    e[4 + side] = static_cast<int8_t>(edgeTarget[side]);
  }
  return e;
}

bool InnerErrorMemo::take(
  const Quadtree& qt, int block, int level, int target, const InnerEdges& edges, PartErrors& errors) const
{
  if (!this->hasLevel(qt, block, level) || this->first[block] < 0)
  {
    return false;
  }
  const std::size_t at = static_cast<std::size_t>(this->first[block]) + static_cast<std::size_t>(level);
  if (this->entries[at].target != target || this->entries[at].edges != edges)
  {
    return false;
  }
  const Entry& e = this->entries[at];
  errors.inner[0] = e.errors[0];
  errors.inner[1] = e.errors[1];
  std::copy(std::begin(e.errorsAt), std::end(e.errorsAt), errors.innerAt);
  errors.innerFrozen = e.frozen;
  ++this->answered;
  return true;
}

void InnerErrorMemo::keep(
  const Quadtree& qt, int block, int level, int target, const InnerEdges& edges, const PartErrors& errors)
{
  if (!this->hasLevel(qt, block, level))
  {
    return;
  }
  if (this->first[block] < 0)
  {
    this->first[block] = static_cast<int32_t>(this->entries.size());
    this->entries.resize(this->entries.size() + qt.blockTopLevels[block]);
  }
  Entry& e = this->entries[static_cast<std::size_t>(this->first[block]) + static_cast<std::size_t>(level)];
  e.errors[0] = errors.inner[0];
  e.errors[1] = errors.inner[1];
  std::copy(std::begin(errors.innerAt), std::end(errors.innerAt), e.errorsAt);
  e.target = static_cast<int8_t>(target);
  e.frozen = errors.innerFrozen;
  e.edges = edges;
}

void InnerErrorMemo::reset(int blocks)
{
  this->first.assign(static_cast<std::size_t>(blocks), -1);
  this->entries.clear();
  this->answered = 0;
}

} // namespace gmm
