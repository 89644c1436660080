// Geomorphing's part errors kept from frame to frame (Morph.h, refreshPartErrors): each
// drawn block's errors follow its key, reused where they can be and measured where they
// cannot, the measuring spread over the cores and, past the frame's limit, left to later
// frames with the error table's bounds meanwhile.
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

// A block's part errors depend on its level and target, and per side on the edge level,
// whether the block's own cells reach a coarser edge (a glided edge: 32 is added to that
// side's edge level; on a coarser block's side the cuts change no surface) and the edge
// target.
std::array<int8_t, 10> keyOf(const BlockConfig& cfg, int target, const std::array<MorphEdge*, 4>& edges)
{
  auto side = [&cfg](int s) {
    return static_cast<int8_t>(cfg.edgeLevel[s] + (cfg.sampleLevel[s] >= 0 && !cfg.cutsSide(s) ? 32 : 0));
  };
  return { static_cast<int8_t>(cfg.level), side(0), side(1), side(2), side(3), static_cast<int8_t>(target),
    edges[0]->target, edges[1]->target, edges[2]->target, edges[3]->target };
}
// The targets its four edges move toward (-1: not moving), as the part errors take them.
std::array<int, 4> edgeTargetsOf(const std::array<MorphEdge*, 4>& edges)
{
  return { edges[0]->target, edges[1]->target, edges[2]->target, edges[3]->target };
}

// About how many samples measuring `parts` of `block` at `level` rasterises: the block for
// its inner grid, a side times the ring's width (a strip reaches from the border to the
// inner ring, one cell of the level in) for each strip. What the frame's limit counts.
std::size_t partSamples(const Quadtree& qt, int block, int level, unsigned parts)
{
  const std::size_t w = static_cast<std::size_t>(qt.blockWidth(block)) + 1;
  const std::size_t h = static_cast<std::size_t>(qt.blockHeight(block)) + 1;
  const std::size_t ring = (std::size_t{ 1 } << std::min(level, 30)) + 1;
  std::size_t samples = (parts & 1u) ? w * h : 0;
  for (int side = 0; side < 4; ++side)
  {
    if (parts & (2u << side))
    {
      samples += (side == South || side == North ? w : h) * std::min(ring, side == South || side == North ? h : w);
    }
  }
  return samples;
}

// Past the frame's limit (MorphCache::measureLimit): keeps measuring the blocks with the
// tightest budgets (the nearest: where the factors matter most and tables prove least),
// in that order until the limit. The other blocks are deferred (cache.deferred): their
// parts keep the error table's bounds that refreshPartErrors wrote for them whatever their
// budget, which are certified but above the budget, so the factors they give are smaller
// than the measured ones; a block with a part the table could not bound does not morph
// this frame at all, and forgets its key. The next frames measure both (boundedPartsOver,
// a changed key), each frame again up to its limit.
void deferPastLimit(const Quadtree& qt, const MorphFrame& out, MorphCache& cache)
{
  std::vector<std::pair<std::size_t, unsigned>>& measures = cache.measures;
  std::size_t total = 0;
  for (const auto& m : measures)
  {
    total += partSamples(qt, out.blocks[m.first], cache.configs[m.first].level, m.second);
  }
  if (total <= cache.measureLimit)
  {
    return;
  }
  std::stable_sort(measures.begin(), measures.end(),
    [&cache](const auto& a, const auto& b) { return cache.budgets[a.first] < cache.budgets[b.first]; });
  std::size_t samples = 0, kept = 0;
  for (const auto& m : measures)
  {
    samples += partSamples(qt, out.blocks[m.first], cache.configs[m.first].level, m.second);
    if (samples <= cache.measureLimit || kept == 0) // at least one: a limit below a block's parts still moves
    {
      measures[kept++] = m;
      continue;
    }
    MorphBlockState& state = cache.slots[cache.drawnSlots[m.first]];
    if (m.second & ~state.errors.bounded)
    {
      cache.deferred[m.first] = kMorphHeld;
      state.key.fill(-2);
      state.errors.bounded = 0;
    }
    else
    {
      cache.deferred[m.first] = kMorphBounded;
    }
  }
  measures.resize(kept);
}
} // namespace

void refreshPartErrors(const Heightfield& hf, const Quadtree& qt, const MorphFrame& out, MorphCache& cache,
  const ErrorTable* table)
{
  const std::vector<int>& drawn = out.blocks;
  std::vector<std::pair<std::size_t, unsigned>>& measures = cache.measures;
  measures.clear();
  cache.deferred.assign(drawn.size(), kMorphMeasured);
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
      if ((parts & 1u) &&
        cache.inner.take(qt, b, cfg.level, out.blockTarget[b],
          innerEdgesOf(cfg, out.blockTarget[b], edgeTargetsOf(cache.edges[k])), state.errors))
      {
        parts &= ~1u;
        state.errors.bounded &= ~1u;
      }
      state.key = key;
    }
    // Bounds kept from a frame with a larger budget may no longer prove their part.
    const double budget = cache.budgets[k];
    parts |= boundedPartsOver(state.errors, budget);
    state.errors.bounded &= ~parts; // bounded again below or measured
    if (parts && table)
    {
      parts &= ~tablePartBounds(hf, *table, qt, b, cfg, out.blockTarget[b], edgeTargetsOf(cache.edges[k]), parts,
        budget, state.errors, cache.scratch, &cache.polylines);
    }
    if (parts)
    {
      measures.emplace_back(k, parts);
    }
  }
  if (cache.measureLimit > 0 && !cache.firstFrame)
  {
    deferPastLimit(qt, out, cache);
  }
  for (const auto& m : measures)
  {
    cache.slots[cache.drawnSlots[m.first]].errors.bounded &= ~m.second; // measured below: exact
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
    const int b = drawn[m.first];
    if (m.second & 1u)
    {
      const BlockConfig& cfg = cache.configs[m.first];
      cache.inner.keep(qt, b, cfg.level, out.blockTarget[b],
        innerEdgesOf(cfg, out.blockTarget[b], edgeTargetsOf(cache.edges[m.first])),
        cache.slots[cache.drawnSlots[m.first]].errors);
    }
  }
}

} // namespace gmm
