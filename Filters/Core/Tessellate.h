// Tessellation: one block at one level, stitched to its neighbours, as triangle indices
// into the full-resolution vertex array (vertex = j*nx + i; nothing is duplicated).
//
// A ring-shaped block (see Levels.h) is made of an inner grid over its inner samples (one
// drawHStrip per row band) and four side strips between the block's edge and its inner
// ring. An edge is drawn as the polyline through its samples at the coarser of its two
// blocks' levels (the edge level). Between two drawn blocks whose finer one is a ring, the
// edge is glided (BlockConfig::sampleLevel): the finer block's strip is a row of its own
// cells up to the edge, its samples there drawn on the polyline (EdgeHeights.h), and the
// coarser block cuts its triangles' sides on the edge at those samples (EdgeCutSink), which
// lie on them: so a block's cells nest in its next level up to its border. Elsewhere
// (beside a merged node, a one-quad finer block, a side at full resolution) the strip joins
// the edge samples to the inner ring by fans (drawFan, any level to any other, difference
// > 1 included). Both blocks of a shared edge derive its samples from the two levels alone,
// so they agree and no crack or T-junction can appear. Triangles are counter-clockwise seen
// from +z in world coordinates.
//
// Drawing follows Poyart et al.: each drawn block or merged node draws its area and its
// east and south connects (drawArea: the main area, drawEastConnect, drawSouthConnect;
// drawMergedArea). A connect is the band between two blocks' inner rings: the block's strip
// on that side and the strip of the drawn block across it, both ending on the shared edge
// at the edge level (a merged node's connect has only the strips across: its fan reaches
// the edge). A block's west and north strips are thus drawn by the connects of what lies
// west and north of it, or by its own main area where nothing drawn lies across (the DEM's
// border, culled space). Every triangle is still one block's (emitBlock) or one node's
// fan, which is what the error table certifies; only who emits it follows the paper.
//
// Triangles touching a nodata (NaN) sample are not emitted. A block with nodata at a level
// above 0 is drawn cell by cell around the nodata (HoleCells.h), over its extent but for
// the border rows of its level's cells that hold no nodata, which side strips draw as any
// ring block's do. A side whose border row holds nodata is sampled at full resolution on
// both sides of the edge, whatever the levels (Quadtree::sideAtFullResolutionAt).
#pragma once

#include "GridTypes.h"
#include "HoleCells.h"
#include "Heightfield.h"
#include "Quadtree.h"

#include <array>
#include <cstdint>
#include <vector>

namespace gmm
{

// Part of a block to emit: the whole block, its inner grid only, or one side strip only.
// The error table rasterises parts separately; drawing uses Whole.
enum class BlockPart
{
  Whole,
  Inner,
  StripSouth,
  StripEast,
  StripNorth,
  StripWest
};

struct BlockConfig
{
  int level = 0;                        // the block's own level (valid for the block)
  // Per side: >= level (the coarser neighbour's) or == level; 0 (every sample) on a side at
  // full resolution (Quadtree::sideAtFullResolutionAt). The side's drawn polyline is the
  // edge's samples at this level.
  std::array<int, 4> edgeLevel{ 0, 0, 0, 0 };
  // Per side: -1 for an edge drawn with its samples at edgeLevel; else a glided edge
  // (sampleLevelOf), whose vertices are its samples at this finer level, those between
  // edgeLevel's glided onto edgeLevel's polyline (sideBaseHeight). The finer block of the
  // edge (sampleLevel == level < edgeLevel) then draws its own cells up to its border; the
  // coarser one (sampleLevel < level == edgeLevel) draws its own triangles with their sides
  // on the edge cut at those samples, which lie on them: the same surface.
  std::array<int, 4> sampleLevel{ -1, -1, -1, -1 };
  // The level of the samples a side strip's edge line starts from: the block's own on a
  // glided edge (the coarser block then cuts its triangles at sampleLevel), else edgeLevel.
  int stripEdgeLevel(int side) const { return sampleLevel[side] >= 0 ? level : edgeLevel[side]; }
  // Whether the triangles on `side` are cut at the finer samples of a glided edge.
  bool cutsSide(int side) const { return sampleLevel[side] >= 0 && sampleLevel[side] < level; }
  // The level of the samples drawn along `side` (a vertex each).
  int drawnEdgeLevel(int side) const { return sampleLevel[side] >= 0 ? sampleLevel[side] : edgeLevel[side]; }
  bool operator==(const BlockConfig& o) const
  {
    return level == o.level && edgeLevel == o.edgeLevel && sampleLevel == o.sampleLevel;
  }
};

// The points along each side of a cell (Side order), for drawing it between two sides.
struct EmitSides
{
  std::array<std::vector<GridPoint>, 4> points;
};

// Buffers emitBlock needs; a caller that emits many parts (the error table) keeps one so
// that emitting allocates nothing once they have grown.
// A ring block's level grid, as the side strips need it to split their regular quads
// (drawSideLines): the block's south-west sample, its level, and its cells a side.
struct RingGrid
{
  int i0 = 0, j0 = 0, level = 0, cellsU = 0, cellsV = 0;
};

struct EmitScratch
{
  RingGrid ring; // of the block whose side lines are in outer / inner (sidePolylines)
  std::vector<int> cols, rows, edge;
  std::vector<GridPoint> outer, inner;
  std::vector<GridPoint> stripStart, stripEnd; // a side strip's ends on the border (HoleCells.h)
  HoleCells cells;
  EmitSides sides;
};

// Appends the block's own triangles (3 indices each) to `out`: its inner part and the strips
// `part` names, whoever draws them in a frame (drawArea). Indices are emitted even when a
// vertex is NaN if `keepNodata` is true (used by the error table to see holes). The form
// with a scratch allocates nothing once its buffers have grown: the engine emits every
// changed block of a frame through one (at 4-quad leaves a from-scratch frame spent a
// quarter of its time allocating the buffers of the other form).
void emitBlock(const Heightfield& hf, const Quadtree& qt, int block, const BlockConfig& config,
  BlockPart part, std::vector<uint32_t>& out, bool keepNodata = false);
void emitBlock(const Heightfield& hf, const Quadtree& qt, int block, const BlockConfig& config,
  BlockPart part, std::vector<uint32_t>& out, EmitScratch& scratch, bool keepNodata = false);

// Any parts of a block at once (emitBlock's BlockPart names one): its inner part (the inner
// grid, or the cells of a block with nodata; a one-quad or thin block, which has no strips,
// is drawn only with its inner part and every side) and any of its side strips.
struct BlockParts
{
  bool inner = false;
  std::array<bool, 4> side{ false, false, false, false };
  bool everySide() const { return side[0] && side[1] && side[2] && side[3]; }
};
void emitBlockParts(const Heightfield& hf, const Quadtree& qt, int block, const BlockConfig& config,
  const BlockParts& parts, std::vector<uint32_t>& out, EmitScratch& scratch);

// The same triangles as grid points, nodata or not (for the error table, which needs the
// grid positions and sees holes itself). `out` is appended to.
void emitBlockGrid(const Quadtree& qt, int block, const BlockConfig& config, BlockPart part,
  std::vector<GridTriangle>& out, EmitScratch& scratch);

// The two polylines a ring block's side strip joins (valid for BlockShape::Ring only):
// scratch.outer gets the edge samples at config.stripEdgeLevel(side) along the block's border,
// scratch.inner the inner ring's samples along that side (the block's own level, one step
// in from the border), both in the block's counter-clockwise direction. Every strip
// triangle has its vertices on these two lines, which are one row (South, North) or
// column (East, West) each. scratch.cols (South, North) or rows (East, West) gets the
// block's samples at its level along the side.
// A block with nodata at a level above 0 has strips only on the sides whose border row is
// clear of nodata (HoleCells.h): `cells` are then its cells at config.level
// (buildHoleCells, cells.strip[side]), whose vertices on the strip's inner line are the
// inner polyline, and scratch.stripStart and stripEnd get the strip's ends on the border
// (stripEnds); nullptr for a block without nodata.
void sidePolylines(const Quadtree& qt, int block, const BlockConfig& config, int side,
  EmitScratch& scratch, const HoleCells* cells = nullptr);
// The side strip between the polylines sidePolylines left in `lines` (appended): the same
// triangles as emitBlockGrid's part for that side, without finding the lines again.
void emitSidePolylinesGrid(const EmitScratch& lines, int side, std::vector<GridTriangle>& out);
// The cells of a block with nodata (buildHoleCells) as grid points, appended: the same
// triangles as emitBlockGrid's Inner part at their level, without building them again.
// `scratch` is for the cells' perimeters; `cells` may be scratch.cells.
void emitHoleCellsGrid(const HoleCells& cells, std::vector<GridTriangle>& out, EmitScratch& scratch);

// Merged nodes (hierarchical selection): a quadtree node drawn whole, far from the eye,
// instead of one coarsest block per leaf. It is drawn as a fan from the block corner its
// children share (mergedCentre) to its perimeter, and the perimeter passes through every
// block corner on the node's border and nothing else, but for every sample along sides at
// full resolution (beside a block with nodata). Over 2 x 2 blocks without such sides the
// fan is exactly its four blocks drawn as one quad each (oneQuadAntiDiagonal, Quadtree.h),
// so merging them, or splitting the node back into them, changes nothing drawn. A block
// beside it draws that side with its corners only (the edge at the block's top level), and
// a merged neighbour has the same points along the shared line (band boundaries are
// global), so no crack or T-junction can appear. That full perimeter does not depend on the
// neighbours' levels: its error is one number per node (ErrorTable::mergedError); a coarse
// one (below) does, and its table bounds it whatever they add.
// Blocks below a merged node carry kCoveredLevel in the level list.
constexpr int8_t kCoveredLevel = -2;

// True when a block with this entry of a level list is drawn: by itself (a level >= 0) or
// as part of a merged node.
inline bool drawnLevel(int level)
{
  return level >= 0 || level == kCoveredLevel;
}

// True when `node` may be drawn whole: a node over at least 2 x 2 blocks (fewer
// triangles than its blocks at their coarsest, and a centre sample strictly inside).
bool mergeableNode(const Quadtree& qt, int node);

// True when `node`'s fan is exactly its blocks drawn at their top level: 2 x 2 blocks, each
// one quad there, none with a side at full resolution (see above). Merging a larger node,
// or splitting it, changes the surface by up to its fan's error and its children's.
bool mergeNestsInBlocks(const Quadtree& qt, int node);

// The apex of a mergeable node's fan: the block corner where the quadtree splits it into
// its children (splitBand: its middle when it spans a power of two of like blocks).
GridPoint mergedCentre(const Quadtree& qt, int node);

// The perimeter of a node, counter-clockwise in (i, j) from its south-west corner: every
// block corner on its border, corners included, each once, and every sample along a
// border block's side at full resolution (a block with nodata across it,
// Quadtree::sideAtFullResolution).
void mergedPerimeter(const Quadtree& qt, int node, std::vector<GridPoint>& out);

// Coarse perimeters (CoarsePerimeter.h): a merged node whose error allows it draws its fan
// to fewer points, those of the depth-d partition of its border (its band ranges split d
// times by splitBand; depth >= the node's height: every block corner, as above), plus
// every point the drawn neighbours across need: the corners of a block drawn by itself,
// and the points of a merged node's own perimeter. Both sides of a shared line then have
// the same points, the union of what each wants, so no crack or T-junction appears. What
// a perimeter depends on in a frame: the level list and, per quadtree node, the perimeter
// depth of each node drawn whole (-1 for the others).
struct PerimeterContext
{
  const std::vector<int8_t>& levels;
  const std::vector<int8_t>& depth;
};

// Whether band boundary c (a block column or row) is an end of one of the ranges that
// splitting [b0, b1) `depth` times by splitBand gives.
bool partitionBoundary(int b0, int b1, int depth, int c);

// The node's perimeter, counter-clockwise from its south-west corner like mergedPerimeter,
// at perimeter depth `depth` (< the node's height), with the points the neighbours across
// want when `across` is given (else the node's own only). The node has no side at full
// resolution (perimeterCoarsens, CoarsePerimeter.h).
void coarsePerimeter(const Quadtree& qt, int node, int depth, const PerimeterContext* across,
  std::vector<GridPoint>& out);

// A merged node's fan, as indices (appended; triangles over nodata dropped as in
// emitBlock) or as grid points (appended, nodata or not). The scratch's `outer` holds the
// perimeter. `across` given: the node's perimeter is at its depth there (coarsePerimeter),
// else every block corner.
void emitMergedNode(const Heightfield& hf, const Quadtree& qt, int node, std::vector<uint32_t>& out);
void emitMergedNode(const Heightfield& hf, const Quadtree& qt, int node, std::vector<uint32_t>& out,
  EmitScratch& scratch, const PerimeterContext* across = nullptr);
void emitMergedNodeGrid(const Quadtree& qt, int node, std::vector<GridTriangle>& out);

// Whether `block`, at a one-quad level (Levels.h) with `config`, is drawn as one cell over
// every sample of its sides at full resolution instead of two triangles, with `fine`
// those sides: it has such a side (edge level 0 at a level above 0, blockConfigOf),
// whose samples its neighbour draws, and is at least 2 quads either way. (A block one
// quad wide lies in a DEM one quad wide: its long sides have no neighbour and its short
// sides no sample between their corners.)
bool oneQuadFineSides(const Quadtree& qt, int block, const BlockConfig& config, bool fine[4]);

// Edge level of each side of `block` given every block's level (-1 = not drawn,
// kCoveredLevel = drawn by a merged node): 0 on a side at full resolution at these levels
// (Quadtree::sideAtFullResolutionAt), else the coarser of the two blocks when the neighbour
// is drawn, the block's top level (corners only) beside a merged node, else the block's
// own level; and each side's sample level (sampleLevelOf).
BlockConfig blockConfigOf(const Quadtree& qt, const std::vector<int8_t>& levels, int block);

// One side of blockConfigOf: the edge level of `side` of `block` drawn at `level`, with
// `neighbour` (blockNeighbours' entry, -1 at the DEM's border) across it. Inline: the
// selection's strip pass (fixStrips) asks it for the sides of every block it rechecks.
inline int edgeLevelOf(const Quadtree& qt, const std::vector<int8_t>& levels, int block,
  int level, int side, int neighbour)
{
  int nl = neighbour >= 0 ? levels[neighbour] : -1;
  if (qt.sideAtFullResolutionAt(block, level, side, neighbour, nl))
  {
    return 0; // beside nodata that reaches the border rows: every sample
  }
  if (nl == kCoveredLevel)
  {
    nl = qt.blockTopLevel(block); // corners only, as the merged node's perimeter has them
  }
  return nl > level ? nl : level;
}

// One side of blockConfigOf's sample levels (BlockConfig::sampleLevel): the level of the
// finer of the two blocks of the edge when the levels differ and that block is drawn as a
// ring at its level (it then draws its own cells up to the edge, their samples on the
// edge glided onto the coarser level's polyline), else -1 (the edge drawn at `edgeLevel`,
// edgeLevelOf's answer for the side): beside a merged node, culled space, the DEM's border,
// on a side at full resolution, and where the finer block is one quad (its corners only).
// Both blocks of an edge answer alike.
inline int sampleLevelOf(const Quadtree& qt, const std::vector<int8_t>& levels, int block, int level,
  int neighbour, int edgeLevel)
{
  const int nl = neighbour >= 0 ? levels[neighbour] : -1;
  if (nl < 0 || nl == level || edgeLevel == 0)
  {
    return -1;
  }
  const bool mineFiner = level < nl;
  const int finer = mineFiner ? level : nl;
  return qt.blockIsRingAt(mineFiner ? block : neighbour, finer) ? finer : -1;
}

// The levels blockConfigOf reads: the block's, then its neighbours' in blockNeighbours'
// order (kNoNeighbour beyond the DEM's border). Two level lists that agree on them give
// the block the same configuration.
using LevelsAround = std::array<int8_t, 5>;
constexpr int8_t kNoNeighbour = -128;
LevelsAround levelsAround(const Quadtree& qt, const std::vector<int8_t>& levels, int block);

// What drawArea's triangles for `block` depend on: its configuration but for the west /
// north edge and sample levels whose strips a neighbour draws (-1 there), and the level,
// edge level and sample level of the strips it draws for its east and south neighbours
// (-1s where it draws none: no drawn block across, or one drawn as its one quad, which has
// no strip).
// Two frames with equal keys draw the block's slot alike (the engine keeps the slot then).
struct DrawnSides
{
  BlockConfig config;
  // East, south: the level of the block across, the shared edge's level and sample level.
  std::array<std::array<int8_t, 3>, 2> across{ { { -1, -1, -1 }, { -1, -1, -1 } } };
  bool operator==(const DrawnSides& o) const { return config == o.config && across == o.across; }
};
DrawnSides drawnSidesOf(const Quadtree& qt, const std::vector<int8_t>& levels, int block,
  const BlockConfig& config);

// Poyart's drawArea: appends what a drawn block draws in a frame, from its key (drawnSidesOf
// of its blockConfigOf): its main area (inner grid or cells or its one quad, and its west
// and north strips where nothing drawn lies across them), then drawEastConnect and
// drawSouthConnect (its east / south strip and the west / north strip of the drawn block
// across). The block's own parts are emitted in one pass; the strips across after. Over
// all drawn blocks this is every block's emitBlock(Whole), each triangle once.
void drawArea(const Heightfield& hf, const Quadtree& qt, int block, const DrawnSides& key,
  std::vector<uint32_t>& out, EmitScratch& scratch);

// Poyart's drawArea for a merged node: its fan (emitMergedNode), then its east and south
// connects: the west / north strips of the drawn blocks along its east / south side, any
// number of them of any sizes (a merged node across draws none: their perimeters meet).
// The connects change only with those blocks' drawArea (their keys, DrawnSides).
// `nodeDepth` given: the drawn merged nodes' perimeter depths (PerimeterContext), else
// every merged node's perimeter has every block corner.
void drawMergedArea(const Heightfield& hf, const Quadtree& qt, const std::vector<int8_t>& levels,
  int node, std::vector<uint32_t>& out, EmitScratch& scratch, const std::vector<int8_t>* nodeDepth = nullptr);

// Tessellates every drawn block (levels[b] >= 0, each a valid level of its block) in
// block order with drawArea, then the merged nodes listed in `merged` (their blocks at
// kCoveredLevel) in node order with drawMergedArea: the order of Engine::indices(). `out`
// is cleared first. `mergedDepth`, given, holds the perimeter depth of each listed node
// (CoarsePerimeter.h; Engine::mergedNodeDepths), else every perimeter is full.
void tessellate(const Heightfield& hf, const Quadtree& qt, const std::vector<int8_t>& levels,
  std::vector<uint32_t>& out, const std::vector<int>& merged = {},
  const std::vector<int8_t>* mergedDepth = nullptr);

} // namespace gmm
