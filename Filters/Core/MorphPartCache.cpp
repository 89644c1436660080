// Geomorphing's part errors kept from frame to frame (Morph.h, refreshPartErrors): each
// drawn block's errors follow its key, reused where they can be and measured where they
// cannot, the measuring spread over the cores.
#include "Morph.h"

#include "Parallel.h"

#include <algorithm>
#include <utility>

namespace gmm
{

namespace
{
// Below this many blocks to measure a frame measures them on the calling thread: starting
// threads costs more than the few blocks a smooth flight changes (about 10 us a block at
// level 0 of block 32).
constexpr std::size_t kParallelMeasures = 32;

std::array<int8_t, 10> keyOf(const BlockConfig& cfg, int target, const std::array<MorphEdge*, 4>& edges)
{
  return { static_cast<int8_t>(cfg.level), static_cast<int8_t>(cfg.edgeLevel[0]),
    static_cast<int8_t>(cfg.edgeLevel[1]), static_cast<int8_t>(cfg.edgeLevel[2]),
    static_cast<int8_t>(cfg.edgeLevel[3]), static_cast<int8_t>(target), edges[0]->target,
    edges[1]->target, edges[2]->target, edges[3]->target };
}
// The targets its four edges move toward (-1: not moving), as the part errors take them.
std::array<int, 4> edgeTargetsOf(const std::array<MorphEdge*, 4>& edges)
{
  return { edges[0]->target, edges[1]->target, edges[2]->target, edges[3]->target };
}
} // namespace

void refreshPartErrors(const Heightfield& hf, const Quadtree& qt, const MorphFrame& out, MorphCache& cache,
  const ErrorTable* table)
{
  const std::vector<int>& drawn = out.blocks;
  std::vector<std::pair<std::size_t, unsigned>>& measures = cache.measures;
  measures.clear();
  for (std::size_t k = 0; k < drawn.size(); ++k)
  {
    const int b = drawn[k];
    if (out.blockTarget[b] < 0 || cache.budgets[k] < 0.0)
    {
      continue; // does not morph: no errors kept
    }
    MorphBlockState& state = cache.slots[cache.drawnSlots[k]];
    const BlockConfig& cfg = cache.configs[k];
    const std::array<int8_t, 10> key = keyOf(cfg, out.blockTarget[b], cache.edges[k]);
    unsigned parts = 0;
    if (key != state.key && key == state.previousKey)
    {
      std::swap(state.key, state.previousKey); // part errors depend on the key only
      std::swap(state.errors, state.previousErrors);
    }
    else if (key != state.key)
    {
      state.previousKey = state.key;
      state.previousErrors = state.errors;
      parts = changedMorphParts(state.key, key);
      if ((parts & 1u) && cache.inner.take(qt, b, cfg.level, out.blockTarget[b], state.errors))
      {
        parts &= ~1u;
        state.errors.bounded &= ~1u;
      }
      state.key = key;
    }
    // Bounds kept from a frame with a larger budget may no longer prove their part.
    const double budget = cache.budgets[k];
    parts |= boundedPartsOver(state.errors, budget);
    if (parts && table)
    {
      parts &= ~tablePartBounds(hf, *table, qt, b, cfg, out.blockTarget[b], edgeTargetsOf(cache.edges[k]), parts,
        budget, state.errors, cache.scratch);
    }
    if (parts)
    {
      state.errors.bounded &= ~parts; // measured below: exact
      measures.emplace_back(k, parts);
    }
  }

  // Each measure writes its own slot's errors and reads only the frame: independent.
  auto measure = [&](const std::pair<std::size_t, unsigned>& m, MorphPartScratch& scratch) {
    const std::size_t k = m.first;
    const int b = drawn[k];
    updateMorphPartErrors(hf, qt, b, cache.configs[k], out.blockTarget[b], edgeTargetsOf(cache.edges[k]), m.second,
      cache.slots[cache.drawnSlots[k]].errors, scratch);
  };
  if (measures.size() < kParallelMeasures)
  {
    for (const auto& m : measures)
    {
      measure(m, cache.scratch);
    }
  }
  else
  {
    const unsigned workers = workerCount(0, measures.size());
    if (cache.workerScratch.size() + 1 < workers)
    {
      cache.workerScratch.resize(workers - 1);
    }
    parallelItems(measures.size(), static_cast<int>(workers), [&](unsigned worker, std::size_t i) {
      measure(measures[i], worker == 0 ? cache.scratch : cache.workerScratch[worker - 1]);
    });
  }

  for (const auto& m : measures)
  {
    if (m.second & 1u)
    {
      const int b = drawn[m.first];
      cache.inner.keep(qt, b, cache.configs[m.first].level, out.blockTarget[b],
        cache.slots[cache.drawnSlots[m.first]].errors);
    }
  }
}

} // namespace gmm
