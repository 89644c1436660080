// A ring block with nodata, drawn at a level > 0 cell by cell over its whole extent: the
// cells around the nodata at full resolution, the rest at the block's level, and every
// sample along the block's border.
//
// Without this a block holding any nodata stays at level 0, so a void of a few samples
// costs its whole block at full resolution (on an SRTM3 tile, most of the coarsest
// selection's triangles). Voids cross block borders as often as not (Rainier: 418 of the
// 498 blocks that stayed at level 0 had nodata on their border), so the border is where
// the cells must reach: such a block has no side strips, and every side of it is drawn at
// full resolution by both blocks that share it (Quadtree::sideAtFullResolution), whatever
// their levels. The neighbours' strips join that full-resolution edge (Tessellate.h).
//
// A cell is the quad between two consecutive samples of the level in each direction
// (edgeSamples: 2^m wide, a narrower last one). A cell side is fine when it lies on the
// block's border or is shared with a FullResolution cell; cells are
//   FullResolution: the cell holds nodata (its border included), or has a fine side and is
//                   under 2 quads wide or tall (it has no sample inside for a fan);
//   Fanned:         any other cell with a fine side: a fan over its perimeter, which has
//                   every sample along its fine sides and only its corners elsewhere, from
//                   a corner between two coarse sides (coarseCorner: two triangles fewer,
//                   which on Rainier's coarsest selection saves 11 %), else from its
//                   centre sample;
//   Plain:          two triangles, as drawArea draws every cell of a block without nodata.
// Two cells that share a side then have the same samples along it, and the border has every
// sample as the neighbours' edges do: no crack or T-junction. Only FullResolution triangles
// touch nodata, and those are the data's own holes (drawn, and dropped, as at full
// resolution).
#pragma once

#include "Quadtree.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace gmm
{

enum class CellKind : uint8_t
{
  Plain,
  FullResolution,
  Fanned
};

// The cells of ring block `block` (with nodata) over its level's samples C (columns) and R
// (rows): cell (a, b), a in [0, |C| - 2], b in [0, |R| - 2], spans [C[a], C[a + 1]] x
// [R[b], R[b + 1]] and is kind[b * (|C| - 1) + a] (cellAt).
void classifyHoleCells(const Quadtree& qt, int block, const std::vector<int>& C,
  const std::vector<int>& R, std::vector<CellKind>& kind);

// Triangles drawn from `kind`: 2 per Plain cell, 2 per quad of a FullResolution cell (fewer
// are drawn where they touch nodata), one per perimeter sample of a Fanned cell.
std::size_t holeCellsTriangleCount(
  const std::vector<int>& C, const std::vector<int>& R, const std::vector<CellKind>& kind);

// Cell (a, b) of classifyHoleCells' `kind` (the one place its layout is spelt out).
inline CellKind cellAt(const std::vector<int>& C, const std::vector<CellKind>& kind, int a, int b)
{
  return kind[static_cast<std::size_t>(b) * (C.size() - 1) + a];
}

// Whether the `side` (Tessellate.h's Side) of cell (a, b) is fine: on the block's border
// or shared with a FullResolution cell. A Fanned cell's perimeter has every sample along
// its fine sides.
bool fineCellSide(const std::vector<int>& C, const std::vector<int>& R,
  const std::vector<CellKind>& kind, int a, int b, int side);
// fineCellSide for each side of cell (a, b), in Side order.
void fineCellSides(const std::vector<int>& C, const std::vector<int>& R,
  const std::vector<CellKind>& kind, int a, int b, bool fine[4]);

// The corner (0 south-west, 1 south-east, 2 north-east, 3 north-west) of a Fanned cell
// whose two sides are both coarse, from which it is fanned (its perimeter less two
// triangles); -1 when there is none (fine sides face each other, or three or four are
// fine), and the fan is from the cell's centre sample.
inline int coarseCorner(const bool fine[4])
{
  // Corner k lies between sides k (South, East, North, West) and k - 1 (mod 4).
  for (int k : { 2, 3, 1, 0 }) // away from the south-west first
  {
    if (!fine[k] && !fine[(k + 3) % 4])
    {
      return k;
    }
  }
  return -1;
}

// Triangles of a w x h quad drawn as a Fanned cell: one per perimeter sample (every sample
// along the sides marked fine, Side order, the corners elsewhere), less two when it is
// fanned from a coarse corner (coarseCorner).
std::size_t fannedCellTriangleCount(int w, int h, const bool fine[4]);

// Whether `block`, at a one-quad level (Levels.h), is drawn as one Fanned cell instead of
// two triangles, with `fine` its sides at full resolution: it has such a side
// (Quadtree::sideAtFullResolution), whose samples its neighbour draws, and is at least 2
// quads either way. (A block one quad wide lies in a DEM one quad wide: its long sides have
// no neighbour and its short sides no sample between their corners.)
bool oneQuadFineSides(const Quadtree& qt, int block, bool fine[4]);

} // namespace gmm
