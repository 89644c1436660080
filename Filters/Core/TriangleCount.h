// How many triangles emitBlock (Tessellate.h) draws for a block configuration, without
// drawing them: what a triangle budget is spent on.
//
// The count is that of the block drawn over every sample; a block with NaN samples draws
// fewer (emitBlock drops triangles touching them), so for a budget the count is an upper
// bound. A block with nodata at a level above 0 counts its cells (HoleCells.h), and its
// side strips where the cells leave them its border rows.
#pragma once

#include "ErrorTable.h"
#include "Quadtree.h"
#include "Tessellate.h"

#include <cstddef>

namespace gmm
{

// Triangles of `block` drawn whole at `config` (its level must be valid for the block,
// Levels.h; an invalid one draws nothing and counts 0). A block with nodata at a level
// above 0 is read from table->cellTriangles (plus its strips' steps along their edges)
// when a table with them is given, else its cells are classified here.
std::size_t blockTriangleCount(
  const Quadtree& qt, int block, const BlockConfig& config, const ErrorTable* table = nullptr);

// Triangles of a merged node's fan (Tessellate.h, emitMergedNode): one per perimeter
// point, i.e. 2 x (block columns + block rows) below the node, plus the samples along its
// sides at full resolution.
std::size_t mergedNodeTriangleCount(const Quadtree& qt, int node);

} // namespace gmm
