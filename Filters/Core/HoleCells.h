// The inner grid of a ring block with nodata, drawn at a level > 0 cell by cell: the
// cells around the nodata at full resolution, the rest at the block's level.
//
// Without this a block holding any nodata stays at level 0, so a void of a few samples
// costs its whole block at full resolution (on an SRTM3 tile, most of the coarsest
// selection's triangles). A cell is the quad between two consecutive samples of the level
// in each direction (edgeSamples: 2^m wide, a narrower last one). Cells are
//   FullResolution: the cell holds nodata (its border included), or lies beside such a
//                   cell and is under 2 quads wide or tall (it has no sample inside);
//   Fanned:         beside a FullResolution cell: a fan from its centre sample over its
//                   perimeter, which has every sample along the sides it shares with
//                   FullResolution cells and only its corners elsewhere;
//   Plain:          two triangles, as drawArea draws every cell of a block without nodata.
// Two cells that share a side then have the same samples along it: no crack or T-junction.
// The side strips' inner ring has every sample along the FullResolution cells beside it
// (Tessellate.cpp, sideLines), so the strips meet them alike; a strip that would touch
// nodata there has +inf error, as any strip over nodata.
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

// The inner grid's cells of ring block `block` over its level's samples C (columns) and
// R (rows), |C|, |R| >= 4: cell (a, b), a in [1, |C| - 3], b in [1, |R| - 3], spans
// [C[a], C[a + 1]] x [R[b], R[b + 1]] and is kind[(b - 1) * (|C| - 3) + (a - 1)]. Returns
// A block without nodata has only Plain cells; with fewer than 4 samples either way there
// are no cells (kind is empty).
void classifyHoleCells(const Quadtree& qt, int block, const std::vector<int>& C,
  const std::vector<int>& R, std::vector<CellKind>& kind);

// Triangles of the inner grid drawn from `kind`: 2 per Plain cell, 2 per quad of a
// FullResolution cell (fewer are drawn where they touch nodata), one per perimeter sample
// of a Fanned cell.
std::size_t holeCellsTriangleCount(
  const std::vector<int>& C, const std::vector<int>& R, const std::vector<CellKind>& kind);

// Cell (a, b) of classifyHoleCells' `kind` (the one place its layout is spelt out);
// Plain when `kind` is empty (no cells, or a block without them).
inline CellKind cellAt(const std::vector<int>& C, const std::vector<CellKind>& kind, int a, int b)
{
  return kind.empty() ? CellKind::Plain
                      : kind[static_cast<std::size_t>(b - 1) * (C.size() - 3) + (a - 1)];
}

// Samples the side strip's inner ring along `side` (Tessellate.h's Side) has beyond the
// level's own: every sample along each FullResolution cell on that side of the inner grid
// (what Tessellate.cpp's sideLines adds, for the triangle count).
std::size_t innerRingExtraSamples(
  const std::vector<int>& C, const std::vector<int>& R, const std::vector<CellKind>& kind, int side);

// Whether the `side` (Tessellate.h's Side) of cell (a, b) is shared with a FullResolution
// cell: such a side has every sample in the fan of a Fanned cell.
bool besideFullResolution(const std::vector<int>& C, const std::vector<int>& R,
  const std::vector<CellKind>& kind, int a, int b, int side);

} // namespace gmm
