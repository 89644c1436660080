// What geomorphing keeps by block while the heights are the same, so that a block that
// comes back to a configuration is not measured again: the inner grids' part errors by level
// and edges (InnerErrorMemo) and the sides' polyline distances (SidePolylineMemo); and by
// quadtree node, the fan heights its block corners glide to (FanCornerMemo).
#pragma once

#include "MorphBounds.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace gmm
{

// sidePolylineError by block, side and level, measured once while the heights are the
// same: tablePartBounds asks it for every strip of a power-of-two block whose key changed,
// every block of a frame after a jump of the camera (a fifth of such a frame's morph work
// at 4097^2 before it was kept). A block's entries (4 sides, one per level up to its top, 4
// bytes each) are made the first time it is asked, so memory follows the blocks drawn.
class SidePolylineMemo
{
public:
  float at(const Heightfield& hf, const Quadtree& qt, int block, int side, int level, EmitScratch& scratch);
  // Forgets everything, for `blocks` blocks.
  void reset(int blocks);

private:
  std::vector<int32_t> first; // per block: its first entry (side 0, level 0), or -1
  std::vector<float> values;  // NaN: not measured yet
};

// Inner-grid part errors by block and level, kept while the heights are the same. They
// depend on the block, its level (its target is the next valid level) and its edges where
// those place the target's samples on the border (InnerEdges), so a block that comes back
// to a level with the same edges, whatever the frames between (a jump of the camera,
// another tau, a stretch out of view), takes them instead of rasterising its inner grid
// again: at 4097^2 and tau 1 a frame whose blocks all change configuration spent 45 % of
// its morph time there. A block's entries (one per level below its top, 96 bytes each) are
// made the first time it morphs, so memory follows the blocks drawn (at most 126 MB at
// 16385^2 and block 32, once every block has morphed).
// What of a block's edges its inner grid's errors read (blockVertexTarget): per side, its
// level where coarser than the target (-1 elsewhere), then its target level (-1: still).
using InnerEdges = std::array<int8_t, 8>;
InnerEdges innerEdgesOf(const BlockConfig& config, int target, const std::array<int, 4>& edgeTarget);

class InnerErrorMemo
{
public:
  // The kept errors of `block` at `level` with `target` and `edges` into `errors` (inner,
  // innerFrozen); false when there are none.
  bool take(const Quadtree& qt, int block, int level, int target, const InnerEdges& edges, PartErrors& errors) const;
  // Keeps `errors`' inner part for `block` at `level` with `target` and `edges`.
  void keep(const Quadtree& qt, int block, int level, int target, const InnerEdges& edges, const PartErrors& errors);
  // Forgets everything, for `blocks` blocks.
  void reset(int blocks);
  // Lookups answered from what was kept, since the last reset.
  std::size_t taken() const { return this->answered; }

private:
  // Whether `block` has an entry for `level` once it has entries (a level below its top).
  bool hasLevel(const Quadtree& qt, int block, int level) const;
  struct Entry
  {
    double errors[2] = { 0.0, 0.0 };
    float errorsAt[16] = {}; // PartErrors::innerAt
    int8_t target = -2; // -2: not measured
    bool frozen = false;
    InnerEdges edges{};
  };
  std::vector<int32_t> first; // per block: its first entry (level 0), or -1
  std::vector<Entry> entries;
  mutable std::size_t answered = 0;
};

// The fan morph's targets (FanMorph.h) by quadtree node, kept while the heights are the
// same: a gliding node's corners are asked every frame, and finding each one's fan triangle
// anew was more than half of a frame's LOD update on bench_core's 16385^2 flight (5.5 - 6.2
// ms against 2.7 ms). A node's entries (its interior block corners, row by row) are made
// the first time it glides.
struct FanCornerMemo
{
  std::vector<int32_t> first; // per node: its first entry, or -1
  std::vector<float> heights;
  // Forgets everything, for `nodes` nodes.
  void reset(std::size_t nodes)
  {
    first.assign(nodes, -1);
    heights.clear();
  }
};

} // namespace gmm
