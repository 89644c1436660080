// Geomorphing (de Boer 2000, 3.1; Lindstrom-style vertex morphing as in the NDL notes):
// a drawn block moves each vertex that its next coarser level drops toward the coarse
// surface beneath it, by a per-block factor t in [0, 1], so that a level switch happens
// when the block already looks like the coarser level instead of popping.
//
// Everything is vertical: a vertex keeps its grid position (x, y) and only its height
// moves, h' = h + t (c - h), c the height of the coarse surface at (x, y). Draped textures
// and the slope texture are addressed by grid position, so nothing swims.
//
// Which vertices move, and where to (morphedHeight, mirrored in the mapper's vertex shader):
// - interior samples of a block at level m (strictly inside its border): toward the block's
//   next valid level m' with its own edges, i.e. the grid C' x R' (edgeSamples at m') split
//   along (i, j)-(i+1, j+1) diagonals, except, in a ring, the south-east and north-west
//   corner cells, split along the other diagonal (Tessellate's corner triangles), and a
//   one-quad m' split along oneQuadAntiDiagonal's diagonal (Quadtree.h). Samples of level m'
//   lie on that grid and do not move. Factor: the block's `blockT`.
// - samples on a shared edge sampled at edge level n: toward the edge polyline at the edge's
//   target level (the next valid level of the block(s) that set the edge level), by the
//   edge's factor. One MorphEdge per shared edge, read by both blocks: the two sides cannot
//   disagree, so morphing opens no crack.
// - block corners move only onto a merging node's fan (FanMorph.h: MorphFrame::cornerT),
//   never with a level change (every level keeps them).
//
// Factors keep the certificate. The drawn height of a part (inner grid, side strip) is
// affine in the factors of its vertices, so its error is bounded by interpolating the exact
// errors of the part with its vertices as drawn and at their targets (MorphBounds.h):
// (1 - t_b) E_0 + t_b E_1 for the inner grid, bilinear in (t_e, t_b) for a strip. Each
// block takes the largest t_b that keeps its inner grid, and its strips with the edges it
// sets moving alike, within tau / f_b; then each edge takes the factor of the block(s)
// setting its level, lowered until the strips on both sides are within their blocks'
// budgets. So the morphed surface is certified at tau like the unmorphed one.
#pragma once

#include "Heightfield.h"
#include "MorphBounds.h"
#include "MorphMemos.h"
#include "MorphRamp.h"
#include "Quadtree.h"
#include "Tessellate.h"

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace gmm
{

// One shared block edge: sampled at `level`, its other samples moving toward the polyline
// at `target` by t. level -1: the edge is not drawn.
struct MorphEdge
{
  int8_t level = -1;
  int8_t target = -1;
  float t = 0.0f;
};

// Per-frame morph data: the only thing that changes from frame to frame.
struct MorphFrame
{
  std::vector<float> blockT;       // per block, interior factor (0 when not drawn)
  std::vector<int8_t> blockTarget; // per block, next valid level (-1: top level or not drawn)
  // Vertical edges: (blockCols + 1) lines x blockRows, index r * (blockCols + 1) + line
  // (line c is the west edge of block column c). Horizontal edges: blockCols x
  // (blockRows + 1) lines, index line * blockCols + c.
  std::vector<MorphEdge> vEdges;
  std::vector<MorphEdge> hEdges;
  // Block corners gliding onto a merging node's fan (FanMorph.h), per corner point (c, r) of
  // the block grid, index r * (blockCols + 1) + c: the factor and the fan's height there
  // (stored units); the corners set are listed in `corners`. Empty, or all 0 but those.
  std::vector<float> cornerT;
  std::vector<float> cornerTarget;
  std::vector<int> corners;
  double maxBoundPixels = 0.0; // certified bound of the morphed surface, max over blocks
  std::vector<int> blocks;     // the drawn blocks the entries above were set for
};


// FrameSettings::geomorphMeasureSamples' default: about 120 blocks of 32 x 32 quads
// measured whole. A jump measured 2.8 M samples a frame at 4097^2; with glided edges an
// edge's change re-measures the parts beside it, and flights of 0.2 blocks a frame over a
// 30 m fractal, at half this, deferred enough of them to pop more (decision record 003).
constexpr std::size_t kDefaultMorphMeasureSamples = std::size_t{ 1 } << 17;

// How a drawn block's part errors stand in a frame (MorphCache::deferred): measured (or
// proven by the table), bounded by the table above its budget while its measurement waits
// for a later frame, or held still (no morph) while it waits.
constexpr uint8_t kMorphMeasured = 0, kMorphBounded = 1, kMorphHeld = 2;

// What computeMorph remembers of one drawn block from frame to frame.
struct MorphBlockState
{
  // The key its part errors are of (level, 4 edge levels, target, 4 edge targets); a
  // changed key recomputes the parts changedMorphParts names.
  std::array<int8_t, 10> key{ -2, -2, -2, -2, -2, -2, -2, -2, -2, -2 };
  PartErrors errors;
  // The key before, with its errors: a block that goes back to it takes them back. Budgeted
  // frames move the blocks at the budget's margin back and forth between two levels (43 -
  // 53 % of the changed keys along bench_core's BM_BudgetFlight; 2 in 17 600 without one).
  std::array<int8_t, 10> previousKey{ -2, -2, -2, -2, -2, -2, -2, -2, -2, -2 };
  PartErrors previousErrors;
  // The rate limit (MorphRamp.h, kMorphSettlePerFrame): the block's drawn continuous level
  // (chain index + factor; -1 when the frame did not follow the path) and projection factor
  // in the last frame.
  double lastLambda = -1.0;
  double lastFactor = 0.0;
  // The pixel rise limit's history (MorphRamp.h, kMorphRisePixels): per side, the edge as
  // drawn in the last frame (its level, target and factor).
  std::array<MorphEdge, 4> lastEdges{};
  int block = -1;
  uint32_t frame = 0; // the last frame (MorphCache::frame) that drew it
};

// Per-block state of the blocks drawn in the last frame, so that a frame computes part
// errors only for blocks whose configuration or targets changed. One per engine.
//
// The state lives in a pool of slots, one per drawn block, packed together: memory follows
// what is drawn (360 bytes a drawn block: 1.3 MB for 3 700 blocks), not the DEM (40 MB of
// part errors at 16385^2, zero-filled at the first frame: 160 ms of fresh pages on the
// benchmark VM). A block that stops being
// drawn gives its slot back; when it is drawn again its errors are computed afresh (they
// depend on the key only).
struct MorphCache
{
  // Input: the most samples (about) a frame rasterises to measure part errors, 0 for no
  // limit. Past it, parts are bounded from the table and measured in later frames, nearest
  // blocks first (refreshPartErrors): a jump of the camera changes nearly every block's
  // key, and measuring them all was 3/4 of such a frame. A frame that follows none drawn
  // (the first) measures everything, so that a flight starts from measured factors.
  std::size_t measureLimit = 0;
  bool firstFrame = true; // per frame (scratch): the last frame drew no block
  std::vector<int32_t> slotOf;          // per block: its slot, or -1
  std::vector<MorphBlockState> slots;
  std::vector<int32_t> freeSlots;
  std::vector<int32_t> held;            // the slots of the last frame's drawn blocks
  uint32_t frame = 0;                   // frames computed with this cache
  const void* heights = nullptr;        // the heights the errors are of (reset on change)
  MorphPartScratch scratch;
  std::vector<MorphPartScratch> workerScratch; // for the threads beyond the calling one
  InnerErrorMemo inner;                 // inner-grid errors by block and level
  SidePolylineMemo polylines;           // sides' polyline distances by block, side and level
  FanCornerMemo fanCorners;             // fan morph targets by node (FanMorph.h)
  // Per frame (scratch): the drawn blocks whose parts are measured (index k into the drawn
  // blocks, and the parts as a MorphBounds.h mask).
  std::vector<std::pair<std::size_t, unsigned>> measures;
  // Per drawn block of a frame (scratch): its slot, its configuration as Tessellate draws
  // it and its four edges, found once and read by every pass.
  std::vector<int32_t> drawnSlots;
  std::vector<BlockConfig> configs;
  std::vector<std::array<MorphEdge*, 4>> edges;
  std::vector<uint8_t> morphs;          // per drawn block: its factors were computed
  std::vector<int> chainAt;             // per drawn block: chainIndex of its level
  std::vector<double> budgets;          // per drawn block: tau / its factor, -1 if it does not morph
  std::vector<uint8_t> deferred;        // per drawn block: kMorphMeasured, kMorphBounded or kMorphHeld
  // Per edge (vEdges, then hEdges; scratch of the pixel rise limit): what its factor may
  // rise to from its setters, and the pixel allowance on top.
  std::vector<std::pair<float, float>> edgeRise;
  std::vector<float> edgeWas; // per drawn block and side: its edge's factor before a refit

  // The rise limit's history of block b: its drawn continuous level in the last frame, or
  // -1 when it was not drawn or that frame did not follow the path.
  double lastLambda(int b) const
  {
    return b >= 0 && b < static_cast<int>(slotOf.size()) && slotOf[b] >= 0 ? slots[slotOf[b]].lastLambda : -1.0;
  }
};

// The parts (MorphBounds.h masks) whose errors a change of a block's key from `was` to `now`
// invalidates: all of them when its level or target changed, else the strips whose edge
// level or edge target did, and where that edge moves or is coarser than the target (the
// target surface's samples on that side are where the edge draws them), the inner grid and
// the strips beside that side too.
unsigned changedMorphParts(const std::array<int8_t, 10>& was, const std::array<int8_t, 10>& now);

// Morph factors for one frame. `levels` and `factor` (pixels per unit of stored height,
// per block) are those of the frame (Engine::levels(), Engine::pixelFactors()); tau the
// pixel error the levels were selected with. A block whose factor is not finite and > 0
// does not morph. `ramp` (Engine::morphRamp()): the level path the frame was selected on;
// a block at its path's level morphs no further than the path's factor, and no block's
// morph rises faster than the path's slope allows since the last call with the same cache
// (MorphRamp.h), so that factors change smoothly with the camera. `drawnBlocks`: the
// blocks with a level >= 0 (Engine::drawnBlocks()), so that a frame costs what it draws;
// without it they are found in `levels`. `drawnConfigs`: per block, the configuration each
// drawn block is tessellated with (Engine::drawnConfigs(), blockConfigOf of `levels`), so
// that it is not derived again; without it it is. Only entries of drawn blocks and their
// edges are written, and those of the previous frame on `out` reset. `table`: the terrain's
// error table (Engine::errorTable()); with it, parts whose table bounds prove them within
// their block's budget are not measured (tablePartBounds): the factors are the same, the
// reported maxBoundPixels may be looser, and a frame whose blocks all change configuration
// (a jump of the camera, another tau) measures fewer parts (on wide 4097^2 views at tau 1,
// 40 - 60 % of the strips are bounded instead).
void computeMorph(const Heightfield& hf, const Quadtree& qt, const std::vector<int8_t>& levels,
  const std::vector<double>& factor, double tau, MorphCache& cache, MorphFrame& out,
  const MorphRamp* ramp = nullptr, const std::vector<int>* drawnBlocks = nullptr,
  const std::vector<BlockConfig>* drawnConfigs = nullptr, const ErrorTable* table = nullptr);

// computeMorph's first pass over the drawn blocks that morph (out.blocks[k] with a target
// and cache.budgets[k] >= 0; cache.drawnSlots, configs and edges filled, and the edges'
// levels and targets set): brings each slot's part errors to the block's key (level, edge
// levels, target, edge targets) and records that key. A block back at its key before takes
// that key's errors; the inner grid comes from cache.inner where kept; the other parts the
// key changed are bounded from `table` where that proves them within the block's budget
// (tablePartBounds; kept bounds that a smaller budget no longer allows are measured again),
// else measured (updateMorphPartErrors), on all cores when many blocks need it (a jump of
// the camera or another tau changes nearly all). Past cache.measureLimit samples, the
// blocks with the loosest budgets take the table's bounds even where those exceed their
// budget (smaller factors, still certified), or without one do not morph, and are measured
// in the frames after, as bounds that no longer prove their part are (cache.deferred says
// which). MorphPartCache.cpp.
void refreshPartErrors(const Heightfield& hf, const Quadtree& qt, const MorphFrame& out, MorphCache& cache,
  const ErrorTable* table = nullptr);

// The four edges of `block` in a frame: South, East, North, West (Tessellate's Side).
std::array<const MorphEdge*, 4> blockEdges(const Quadtree& qt, const MorphFrame& f, int block);

// No morphing at all: every factor 0 (what a frame with geomorphing off draws).
void clearMorph(const Quadtree& qt, MorphFrame& out);

// Height (stored units) the drawn surface gives sample (i, j) under `frame`: its base
// height (the sample's own, or on a glided edge the edge's polyline: EdgeHeights.h) for a
// vertex that does not move. Only meaningful for samples that drawn triangles use.
double morphedHeight(const Heightfield& hf, const Quadtree& qt, const std::vector<int8_t>& levels,
  const MorphFrame& frame, int i, int j);

// The height of the coarse surface a vertex moves toward (its base height when it does not
// move), i.e. morphedHeight at factor 1, and the vertex's factor; exposed for tests.
double morphTarget(const Heightfield& hf, const Quadtree& qt, const std::vector<int8_t>& levels,
  const MorphFrame& frame, int i, int j, double* factorOut);

// The one rule for where a vertex goes: sample (i, j) of `block` (inside or on its border),
// the block drawn with edge levels `edgeLevel`, when the interior moves toward level
// `target` and side s's edge toward the polyline at level `edgeTarget[s]` (-1: does not
// move). Corners never move; an edge vertex goes to that polyline, or stays at its base
// height (EdgeHeights.h, sideBaseHeight) when its edge does not move. The interior's target
// is the block's surface at `target` with its samples on the border where the edges draw
// them at factors `edgeFactor` (from their base heights toward their targets): the surface
// the block draws at that level with the same edges, so that a block switching level with
// its interior fully morphed moves nothing, whatever its edges' factors. Hence an interior
// vertex's drawn height, h + t_b (target - h), is bilinear in its block's factor and its
// edges' (MorphBounds.h).
double blockVertexTarget(const Heightfield& hf, const Quadtree& qt, int block, int target,
  const std::array<int, 4>& edgeTarget, const std::array<int, 4>& edgeLevel, int i, int j,
  const std::array<double, 4>& edgeFactor = { 0.0, 0.0, 0.0, 0.0 });

// A frame without geomorphing: every factor 0, each drawn block's edges at the levels it
// draws them with (the coarser of their blocks'), for the heights of glided edges
// (EdgeHeights.h) that morphedHeight and the mapper's vertex shader give. `drawnBlocks` and
// `drawnConfigs` as computeMorph takes them.
void drawnEdgeFrame(const Quadtree& qt, const std::vector<int8_t>& levels, MorphFrame& out,
  const std::vector<int>* drawnBlocks = nullptr, const std::vector<BlockConfig>* drawnConfigs = nullptr);

} // namespace gmm
