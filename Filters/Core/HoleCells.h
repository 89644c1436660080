// A ring block with nodata, drawn at a level > 0 cell by cell around its nodata: the
// level's cells, split down towards the nodata, and side strips where a side's border row
// of cells holds none.
//
// Without this a block holding any nodata stays at level 0, so a void of a few samples
// costs its whole block at full resolution (on an SRTM3 tile, most of the coarsest
// selection's triangles). Voids cross block borders as often as not (Rainier: 418 of the
// 498 blocks that stayed at level 0 had nodata on their border), so the cells reach the
// border where the nodata does: a side whose border row of cells holds nodata has no strip,
// and is drawn at full resolution by both blocks that share it, whatever their levels; the
// neighbour's strip (or one-quad fan) joins that full-resolution edge (Tessellate.h).
// A side whose border row is clear of nodata (Quadtree::sideClearOfNodata: 2^m < its
// nodata depth) is a side strip like any ring block's, from the block's edge at the edge
// level to the cells' vertices on the row's inner line (innerRingLine), and follows the
// neighbour's level (Quadtree::sideAtFullResolutionAt). Where the side before or after it
// has no strip, the strip ends on the block's border, whose samples there it fans
// (stripEnds). Such strips, and the one-quad blocks beside them that follow them too, cut
// Rainier's coarsest selection from 122 937 to 94 389 triangles (benchmarks-core.md,
// session 13): there, almost every block beside a void is one quad, and a one-quad block
// with a side at full resolution draws 33 triangles instead of 2.
//
// The cells start as the quads between the level's samples (edgeSamples: 2^m wide, a
// narrower last one). A cell holding nodata (its border included) is split in four (in two
// when it is one quad wide or tall) at the next level's samples, down to single quads:
// a restricted quadtree whose smallest cells hold the nodata. Splitting only towards the
// nodata instead of drawing a whole cell at full resolution cut Rainier's coarsest
// selection from 154 373 to 128 717 triangles and N48W125's from 95 305 to 76 343, and
// the drawing below to 122 937 and 74 687 (benchmarks-core.md, session 12).
//
// A cell's vertices are its corners and every other cell's corner on its sides (and every
// sample along the block's border where the cells reach it), so two cells that share a side
// have the same samples along it, and the border has every sample as the neighbours' edges
// do: no crack or T-junction. A cell is drawn as
//   a full-resolution quad: one quad with a nodata corner (drawn, and dropped, as at full
//                           resolution: the data's own hole);
//   two triangles:          no vertex but its corners (on its (i0, j0)-(i1, j1) diagonal);
//   two fewer triangles than vertices otherwise: a fan from a corner between two sides with
//                           no vertex inside them (coarseCorner), else (two opposite sides
//                           have vertices) a strip that zigzags between those two sides,
//                           fanned at its ends where the sides between have vertices
//                           (CellDrawing.h, drawBetweenSides). Every triangle has its
//                           vertices on two lines, so none is degenerate, and no cell needs
//                           a sample inside it. (Fans from the centre sample, before, drew
//                           two more triangles: 2 502 cells of Rainier's coarsest selection.)
// Only the full-resolution quads touch nodata. A block with no valid sample has no cells:
// it draws nothing at any level above 0.
#pragma once

#include "GridTypes.h"
#include "Quadtree.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace gmm
{

// One cell of a block with nodata: [i0, i1] x [j0, j1] in DEM samples.
struct HoleCell
{
  int i0, j0, i1, j1;
  bool nodata; // a single quad with a nodata corner, drawn as at full resolution
};

// The cells of one block at one level (buildHoleCells) and their vertices.
struct HoleCells
{
  // Per side (Side order): true when the side's border row of cells is clear of nodata
  // (Quadtree::sideClearOfNodata). The cells then stop at that row's inner line, and a
  // side strip joins the block's edge to the cells' vertices on it (innerRingLine).
  bool strip[4] = { false, false, false, false };
  int i0 = 0, j0 = 0;        // the first sample column and row of the area the cells cover
  int width = 0, height = 0; // its size in quads
  int blockI0 = 0, blockJ0 = 0, blockI1 = 0, blockJ1 = 0; // the block's corners

  bool anyStrip() const { return strip[0] || strip[1] || strip[2] || strip[3]; }
  std::vector<HoleCell> cells;
  // (width + 1) x (height + 1), row by row from (i0, j0): 1 where a sample is a cell's
  // corner or lies on the block's border (where the cells reach it), i.e. a vertex of every
  // cell whose side it is on.
  std::vector<uint8_t> vertex;
  // Scratch: nodata counts over sample rectangles, the level's samples, cells to split.
  std::vector<uint32_t> nodataBelow;
  std::vector<int> cols, rows;
  std::vector<HoleCell> pending;

  bool isVertex(int i, int j) const
  {
    return vertex[static_cast<std::size_t>(j - j0) * (width + 1) + (i - i0)] != 0;
  }
};

// The cells of ring block `block` (with nodata) at ring level `level` > 0: over the block,
// but for the border rows clear of nodata at that level (Quadtree::sideClearOfNodata),
// which side strips draw. `out` is reused: once its buffers have grown, building allocates
// nothing. `out.cols` and `out.rows` get the block's samples at the level.
void buildHoleCells(const Quadtree& qt, int block, int level, HoleCells& out);

// The inner line of side strip `side` (Tessellate.h's Side order; cells.strip[side]): the
// cells' vertices along that side of the area they cover, in the block's counter-clockwise
// direction, corners included. Where the side before (after) it has no strip, the line
// starts (ends) on the block's border, and so does the strip: the samples of that border
// between the strip's two lines, all vertices as the cells' border there, are then fanned
// from the line's second (second-last) point (stripEnds).
void innerRingLine(const HoleCells& cells, int side, std::vector<GridPoint>& out);

// The ends of side strip `side` that lie on the block's border (see innerRingLine): `start`
// gets the points from the inner line's first point to the edge's first point along the
// border before it, `end` from the edge's last point to the inner line's last point along
// the border after it, each empty where the neighbouring side has a strip too (the strip
// then ends on the diagonal of its corner square, as a ring block's does).
void stripEnds(const HoleCells& cells, int side, std::vector<GridPoint>& start, std::vector<GridPoint>& end);

// Triangles the cells draw (a full-resolution quad: its triangles without a nodata
// corner), and the side strips' triangles that depend on the level alone: one per step
// along their inner lines, and their ends' fans beyond that. A side strip adds one triangle
// per step along its edge too, which depends on the edge level and is the caller's to add.
std::size_t holeCellsTriangleCount(const HoleCells& cells);

// The corner (0 south-west, 1 south-east, 2 north-east, 3 north-west) of a cell whose two
// sides have no vertex inside them (`fine[s]`: side s has), from which it is fanned; -1
// when there is none (such sides face each other, or three or four have vertices), and it
// is drawn between two opposite sides.
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

// Triangles of a cell (or a one-quad block) over `vertices` perimeter points, however it
// is drawn: two fewer.
inline std::size_t cellTriangleCount(std::size_t vertices)
{
  return vertices - 2;
}

// Triangles of a w x h quad drawn over every sample along the sides marked fine (Side
// order) and only the corners elsewhere.
std::size_t fannedCellTriangleCount(int w, int h, const bool fine[4]);

} // namespace gmm
