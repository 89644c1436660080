// Quadtree with variable-size leaves over a heightfield (Poyart et al., 3.1).
//
// Width and height are each cut into bands of a power of two quads, as large as halving
// would make them within `maxBlockQuads` (splitBands, bandWidth), and the quadtree's nodes
// split the bands at powers of two (splitBand). Because a dimension is split by a rule that
// depends on that dimension alone, the leaves form a grid of row bands x column bands: every
// block has exactly one neighbour per side with the same shared edge, which keeps stitching
// exact.
// Leaves share their border samples (block (c, r) covers samples colStart[c]..colStart[c+1]).
#pragma once

#include "Heightfield.h"
#include "Levels.h"

#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace gmm
{

struct Box
{
  glm::dvec3 lo{ 0.0 };
  glm::dvec3 hi{ 0.0 };
};

struct QuadtreeNode
{
  Box box;               // world-space bounds of every valid sample below (z from heights)
  int32_t firstChild = -1; // index of first child in Quadtree::nodes; children are contiguous
  int32_t childCount = 0;  // 0 for a leaf
  int32_t block = -1;      // leaf only: block index (row * blockCols + col)
  // The block columns [colBegin, colEnd) and rows [rowBegin, rowEnd) below the node: it
  // covers samples colStart[colBegin]..colStart[colEnd] x rowStart[rowBegin]..rowStart[rowEnd].
  int32_t colBegin = 0, colEnd = 0, rowBegin = 0, rowEnd = 0;
  int32_t height = 0; // levels down to its deepest leaf (0 for a leaf)
  // Every sample below is nodata (Quadtree::everySampleNodata for each of its blocks): the
  // node draws nothing at any level, so the selection's walks skip it as they skip a node
  // out of view (an SRTM tile on a coast is about half sea).
  bool allNodata = false;
};

struct Quadtree
{
  std::vector<int> colStart; // blockCols + 1 sample columns: block c spans [colStart[c], colStart[c+1]]
  std::vector<int> rowStart; // blockRows + 1 sample rows
  int blockCols = 0;
  int blockRows = 0;
  std::vector<QuadtreeNode> nodes; // nodes[0] is the root
  std::vector<Box> blockBox;       // per block, world bounds (z over valid samples)
  std::vector<uint8_t> blockHasNodata; // per block: any NaN sample inside (borders included)
  std::vector<uint8_t> blockAllNodata; // per block: every sample (borders included) is NaN
  // Per block: its width and height in quads (colStart and rowStart differences), read by
  // every per-block step of a frame: a lookup instead of block % blockCols and
  // block / blockCols (2.6 % of a 4097^2 mapper-default frame's instructions).
  std::vector<int> blockWidths, blockHeights;
  // Per block: its top level (topLevel of its width and height) and how many levels draw it
  // as a ring (levels 0 .. ringLevels - 1; ceilLog2 of its narrow side), for the frame's
  // per-block level rules (geomorphing's chain, the strips' ring tests): a lookup instead of
  // two leading-zero counts and a min.
  std::vector<uint8_t> blockTopLevels, blockRingLevels;
  // Which samples of each block with nodata are nodata (borders included), one bit each,
  // row by row from the block's first row and column, from bit 0 of word
  // nodataBitsAt[block]. Both empty when the DEM has none. What draws such a block at a
  // coarse level (HoleCells.h) reads them instead of the heights.
  std::vector<uint64_t> nodataBits;
  std::vector<uint64_t> nodataBitsAt;
  // nodataDepth[4 * block + side] (Side order: South, East, North, West), per block when
  // the DEM has nodata: how many sample lines in from that side of the block hold no
  // nodata (0 when nodata lies on the side, up to 65535). Empty when the DEM has none.
  // Decides at which levels a side's border row of cells is clear of nodata
  // (sideClearOfNodata).
  std::vector<uint16_t> nodataDepth;
  // Per block column and per block row: 1 when the band is the upper half of the last split
  // that separated it from its sibling (upperHalfBands), which gives every one-quad block
  // its diagonal (oneQuadAntiDiagonal).
  std::vector<uint8_t> colUpperHalf, rowUpperHalf;

  int blockCount() const { return blockCols * blockRows; }
  int blockIndex(int col, int row) const { return row * blockCols + col; }
  // The first node on the path from the root down to block (col, row) for which
  // `flagged(node)` holds, or -1 when none does down to the leaf.
  template <typename Flagged>
  int firstNodeOver(int col, int row, Flagged flagged) const
  {
    int at = 0;
    while (!flagged(at))
    {
      const QuadtreeNode& n = nodes[at];
      int next = -1;
      for (int k = n.firstChild; k < n.firstChild + n.childCount && next < 0; ++k)
      {
        const QuadtreeNode& child = nodes[k];
        next = col >= child.colBegin && col < child.colEnd && row >= child.rowBegin && row < child.rowEnd ? k : -1;
      }
      if (next < 0)
      {
        return -1;
      }
      at = next;
    }
    return at;
  }
  int blockWidth(int block) const { return blockWidths[block]; } // in quads
  int blockHeight(int block) const { return blockHeights[block]; }
  int blockTopLevel(int block) const { return blockTopLevels[block]; }
  int blockRingLevelCount(int block) const { return blockRingLevels[block]; }
  // Whether `block` at level m is a ring: blockShape(width, height, m) == BlockShape::Ring
  // (2^m below both sides, i.e. m < ceilLog2 of the narrow side).
  bool blockIsRingAt(int block, int m) const { return m >= 0 && m < blockRingLevels[block]; }
  // Whether sample (i, j) of `block` (within its rectangle, borders included) is nodata.
  bool sampleIsNodata(int block, int i, int j) const
  {
    if (!blockHasNodata[block])
    {
      return false;
    }
    const int c = block % blockCols, r = block / blockCols;
    const uint64_t bit = static_cast<uint64_t>(j - rowStart[r]) * (colStart[c + 1] - colStart[c] + 1) +
      static_cast<uint64_t>(i - colStart[c]);
    return (nodataBits[nodataBitsAt[block] + bit / 64] >> (bit % 64)) & 1u;
  }
  // Whether every sample of `block` (borders included) is nodata: nothing of it is drawn
  // at any level, and no selection draws it (QuadtreeNode::allNodata).
  bool everySampleNodata(int block) const { return blockAllNodata[block] != 0; }
  // The blocks across the South, East, North and West sides of `block` (Tessellate.h's Side
  // order: low row, high column, high row, low column), -1 where the DEM ends.
  std::array<int, 4> blockNeighbours(int block) const
  {
    const int c = block % blockCols, r = block / blockCols;
    return { r > 0 ? block - blockCols : -1, c + 1 < blockCols ? block + 1 : -1,
      r + 1 < blockRows ? block + blockCols : -1, c > 0 ? block - 1 : -1 };
  }
  // Whether `side` of `block` (blockNeighbours' order) may be drawn with every sample along
  // it: the block or the one across holds nodata (HoleCells.h). Both blocks of an edge
  // answer alike. Whether it is, at given levels, is sideAtFullResolutionAt; merged nodes'
  // perimeters and geomorphing take every such side at full resolution, and the error
  // table measures such a side both ways.
  bool sideAtFullResolution(int block, int side) const
  {
    // A DEM without nodata (no bits) has none: skip the neighbour lookup on hot paths.
    return !nodataBits.empty() && sideAtFullResolutionBeside(block, blockNeighbours(block)[side]);
  }
  // Whether any side of `block` may be (sideAtFullResolution): the block or a neighbour
  // across one of its sides holds nodata.
  bool anySideAtFullResolution(int block) const
  {
    if (nodataBits.empty())
    {
      return false;
    }
    for (int side = 0; side < 4; ++side)
    {
      if (sideAtFullResolution(block, side))
      {
        return true;
      }
    }
    return false;
  }
  // The same for the side shared with `neighbour` (blockNeighbours' entry, -1 at the DEM's
  // border), for callers that have the neighbours already.
  bool sideAtFullResolutionBeside(int block, int neighbour) const
  {
    return !nodataBits.empty() &&
      (blockHasNodata[block] || (neighbour >= 0 && blockHasNodata[neighbour]));
  }
  // Whether no block below `node` holds nodata or has a side at full resolution
  // (anySideAtFullResolution): its fan's perimeter is then block corners only.
  bool nodeClearOfNodata(int node) const
  {
    const QuadtreeNode& n = nodes[node];
    for (int r = n.rowBegin; r < n.rowEnd; ++r)
    {
      for (int c = n.colBegin; c < n.colEnd; ++c)
      {
        const int b = blockIndex(c, r);
        if (blockHasNodata[b] || anySideAtFullResolution(b))
        {
          return false;
        }
      }
    }
    return true;
  }
  // Whether `block`, with nodata, at ring level `level` > 0 holds none in its level's border
  // row of cells along `side` (lines 0 to 2^m in from it). That side is then drawn as a
  // side strip that follows the neighbour's level, to the vertices of the block's cells
  // around its nodata (HoleCells.h).
  bool sideClearOfNodata(int block, int side, int level) const
  {
    return level > 0 && level < 16 && blockHasNodata[block] &&
      (1 << level) < nodataDepth[4 * static_cast<std::size_t>(block) + side] &&
      blockShape(blockWidth(block), blockHeight(block), level) == BlockShape::Ring;
  }
  // Whether `block` at `level` draws `side` at the edge level both blocks agree on (the
  // coarser one), as a block without nodata does: it holds no nodata and is a ring or one
  // quad (corners only) at that level, or holds nodata but none in that side's border row
  // (sideClearOfNodata). A thin block, a block covered by a merged node or not drawn does
  // not.
  bool followsEdgeLevels(int block, int side, int level) const
  {
    if (blockHasNodata[block])
    {
      return sideClearOfNodata(block, side, level);
    }
    const BlockShape shape = blockShape(blockWidth(block), blockHeight(block), level);
    return shape == BlockShape::Ring || shape == BlockShape::OneQuad;
  }
  // Whether `side` of `block` follows the edge levels at some level (followsEdgeLevels).
  bool mayFollowEdgeLevels(int block, int side) const
  {
    return !blockHasNodata[block] || nodataDepth[4 * static_cast<std::size_t>(block) + side] > 2;
  }
  // The one rule of which sides are drawn with every sample at given levels (`level` of
  // `block`, whose `side` it is, `neighbourLevel` of `neighbour` across it, -1 at the DEM's
  // border): a side that may be (sideAtFullResolutionBeside) is, unless both blocks follow
  // the edge levels there (a DEM border follows anything). Tessellation (blockConfigOf) and
  // the selection read it; both blocks of an edge answer alike, so their samples agree.
  bool sideAtFullResolutionAt(int block, int level, int side, int neighbour, int neighbourLevel) const
  {
    return sideAtFullResolutionBeside(block, neighbour) &&
      !(followsEdgeLevels(block, side, level) &&
        (neighbour < 0 || followsEdgeLevels(neighbour, (side + 2) % 4, neighbourLevel)));
  }
};

// The smallest largest-block side, in quads: the one rule every entry point (engine,
// mapper, filter, command-line tools) applies. Below 4, a band of 3 quads can leave a block
// one quad wide between two neighbours, which no block shape stitches.
constexpr int kMinBlockQuads = 4;

// The block size the mapper, the filter, the engine and the tools use unless told otherwise:
// blocks of 32 quads on DEMs of 32 x 2^k quads, 16 on most others (bandWidth). Measured
// (decision record 002, step 4; benchmarks-core.md): against 64, 32 draws half the
// triangles at tau = 1; 16 everywhere draws 55 % fewer than 32 on bench_core's 4097^2
// flight with geomorphing (range 3), for the same CPU, but 9 % (with geomorphing) to 36 %
// (without) more over a whole 16385^2 DEM (its merged nodes' fans pass through 4x as many
// block corners), and geomorphing at range 3 pops more where it merges nodes (mean of the
// frames' worst pop 1.17 against 0.24 px on measure_pop_causes' flight).
constexpr int kDefaultBlockQuads = 32;

// "" when maxBlockQuads is a usable block size (>= kMinBlockQuads), else the reason.
std::string validateBlockSize(int maxBlockQuads);

// The width of a dimension's bands (splitBands): `quads` itself when it is at most
// maxQuads, else the largest power of two (at least 2) not above quads / 2^k, k the fewest
// halvings that bring quads within maxQuads. Blocks are then as large as halving would make
// them (between maxQuads / 4 and maxQuads; maxQuads itself when quads is maxQuads times a
// power of two, as a 2^k + 1 DEM at a power-of-two block size), and a power of two, so that
// each level of a block nests in the next (Levels.h; decision record 002).
int bandWidth(int quads, int maxQuads);

// Splits [0, quads] into bands: from the low end, bands of bandWidth quads, then the
// remainder in a band of its own (a remainder of one quad joins the band before, split in
// two halves, the first rounded down to even, where that band would exceed maxQuads).
// Returns band start positions plus the end (so size = bands + 1). Non-zero collars
// (nodataCollar) first take a band of that many quads at the low and the high end, one
// more where that keeps the next band's start even, and the quads between are split as
// above; a collar that would leave fewer than kMinBlockQuads quads between is dropped.
// Every band starts on an even sample: a block's full-resolution cells are then split as
// the DEM's (the union-jack rule, cellAntiDiagonal in Levels.h, is the same counted from
// the block's corner or from the DEM's), so level 0 is one triangulation of the whole DEM
// (RayCast.h).
std::vector<int> splitBands(int quads, int maxQuads, int lowCollar = 0, int highCollar = 0);

// Band index of sample s in band starts `start` (splitBands' form, bands + 1 entries): the
// band whose first sample is the largest start <= s, clamped into [0, bands) (so the very
// last sample falls in the last band).
inline int bandOfSample(const std::vector<int>& start, int s)
{
  const int bands = static_cast<int>(start.size()) - 1;
  const int k = static_cast<int>(std::upper_bound(start.begin(), start.end(), s) - start.begin()) - 1;
  return std::min(std::max(k, 0), bands - 1);
}

// Nodata collars: the width, in quads, of the nodata that lines each border of the DEM.
// A raster reprojected onto the engine's grid has wedges of nodata along its borders (the
// reader's lon/lat tiles: up to 11 samples on the east and west of an SRTM3 tile at 47 N;
// a UTM quad such as St Helens' USGS DEM), and a block with nodata is drawn cell by cell
// with its border at full resolution (HoleCells.h), far costlier than a clean block (before
// those cells, every border block was drawn at full resolution). A band as wide as the
// collar keeps the wedge in thin blocks and leaves the blocks inside it free of nodata.
// Per side, each line across it (rows for West and East, columns for South and North)
// counts its nodata samples from the border up to the first valid one. The collar is one
// more than the longest count below maxBlockQuads - kMinBlockQuads, so that the band's
// inner column (row) and the one before it are valid on every such line: the blocks
// inside hold no nodata and take any level (their side beside the collar at full
// resolution where the collar's nodata reaches its border row there,
// Quadtree::sideAtFullResolutionAt). A longer run is a void or an empty line, which no
// thin band isolates.
// 0 where no line starts with nodata. Lines within another side's collar are not counted
// (a wedge along the west also starts the first columns with nodata seen from the north).
struct NodataCollar
{
  int west = 0, east = 0, south = 0, north = 0;
};
NodataCollar nodataCollar(const Heightfield& hf, int maxBlockQuads);

// Where buildQuadtree splits a node's range [begin, end) of block columns (or rows): after
// the largest power of two of bands below its count (end when the range is one band, which
// is not split). A power-of-two count halves; an SRTM3 tile's 75 bands of 16 split 64 + 11,
// so that most of a tile lies in nodes of 2^k x 2^k blocks (fans of 2 x 2 one-quad blocks
// nest in them, mergeNestsInBlocks). Ranges start on multiples of their lower part's width.
inline int splitBand(int begin, int end)
{
  const int n = end - begin;
  return n > 1 ? begin + (1 << (ceilLog2(n) - 1)) : end;
}

// For each of `bands` bands (block columns or rows): 1 when it is the upper half of the
// last split that separated it (splitBand). A dimension's ranges do not depend on the
// other's, so in a node of 2 x 2 blocks each block's flags say which of its corners the
// four share.
std::vector<uint8_t> upperHalfBands(int bands);

// Whether block b, drawn as one quad (Levels.h), is split along its (i1, j0)-(i0, j1)
// diagonal instead of (i0, j0)-(i1, j1): the one through the corner it shares with the other
// blocks of a 2 x 2 node, the centre of that node's merged fan (Tessellate.h). Four one-quad
// blocks then draw exactly their node's fan, so merging them moves nothing (a merge that
// changed the surface would pop, geomorphing or not).
inline bool oneQuadAntiDiagonal(const Quadtree& qt, int block)
{
  return qt.colUpperHalf[block % qt.blockCols] != qt.rowUpperHalf[block / qt.blockCols];
}

// Builds the quadtree, with the heightfield's nodata collars as their own bands
// (nodataCollar, splitBands). The heightfield must be valid and maxBlockQuads pass
// validateBlockSize (a smaller value is raised to kMinBlockQuads, so no caller can build
// an unstitchable tree). The blocks' boxes are scanned by up to `threads` threads (0 = the
// hardware's).
Quadtree buildQuadtree(const Heightfield& hf, int maxBlockQuads, int threads = 1);

} // namespace gmm
