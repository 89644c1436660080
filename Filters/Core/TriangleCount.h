// How many triangles emitBlock (Tessellate.h) draws for a block configuration, without
// drawing them: what a triangle budget is spent on.
//
// A block with nodata counts what it draws: emitBlock drops the triangles with a nodata
// corner, and only its full-resolution quads have one (at level 0 every quad, above it the
// cells that hold the nodata, HoleCells.h); above level 0 it counts its cells and its side
// strips where the cells leave them its border rows. (Counting those quads whole, as
// before, made a budget over Rainier's voids stop at 90 k drawn triangles for 150 k
// counted.)
#pragma once

#include "ErrorTable.h"
#include "Quadtree.h"
#include "SelectLevels.h"
#include "Tessellate.h"

#include <cstddef>

namespace gmm
{

// Triangles of `block` drawn whole at `config` (its level must be valid for the block,
// Levels.h; an invalid one draws nothing and counts 0). A block with nodata is read from
// table->cellTriangles (plus its strips' steps along their edges) when a table with them
// is given, else its cells are classified here.
std::size_t blockTriangleCount(
  const Quadtree& qt, int block, const BlockConfig& config, const ErrorTable* table = nullptr);

// Triangles emitBlock draws for `block` at `config`, counted by emitting them as grid
// points and dropping those with a nodata corner (Quadtree::sampleIsNodata): what the
// per-level counts of a block with nodata at level 0 are made of, where the ring's corner
// squares take the strips' diagonals.
std::size_t drawnTriangleCount(const Quadtree& qt, int block, const BlockConfig& config);

// Triangles of a merged node's fan (Tessellate.h, emitMergedNode): one per perimeter
// point, i.e. 2 x (block columns + block rows) below the node, plus the samples along its
// sides at full resolution.
std::size_t mergedNodeTriangleCount(const Quadtree& qt, int node);

// Two triangles a quad for every block whose box meets `frustum` (boxVsFrustum, in the
// quadtree's frame as cullBlocks takes it): the finest selection of the view with every
// such block at level 0, or more than it draws (nodata's cells, nodes of error 0 drawn
// whole). A walk that stops at nodes wholly inside or outside, so it visits the nodes the
// frustum's planes cut, not the DEM's.
std::size_t fullResolutionTrianglesInView(const Quadtree& qt, const Frustum& frustum);

} // namespace gmm
