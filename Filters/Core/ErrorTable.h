// Exact geometric error of every block at every level, and of every side strip for every
// coarser edge level. Computed from the very triangles Tessellate emits over the
// full-resolution samples (RasterError.h): the error of a sample is its vertical distance
// to the drawn triangle above/below it, and a table entry is the maximum over the samples
// it covers.
// A triangle that would cover or touch nodata at anything but full resolution has infinite
// error; a block with nodata takes a coarser level drawn cell by cell (HoleCells.h), with
// the nodata's cells at full resolution, and side strips where the nodata lies inside its
// inner ring. Errors are computed in double
// from height differences (a constant height offset, e.g. ECEF-like 6.4e6 m, gives the very
// same table; a plane gives exactly 0) and rounded up to float, never below the exact value.
// +inf means only "level not allowed": heights are bounded (kMaxHeight), so no real error
// overflows.
#pragma once

#include "Heightfield.h"
#include "Quadtree.h"
#include "Tessellate.h"

#include <cstdint>
#include <functional>
#include <vector>

namespace gmm
{

// Merged nodes up to this height above the leaves (16 x 16 blocks), or up to
// kExactMergedQuads quads on their longer side, have exact errors; the others a bound
// (mergedErrorIsExact). The extent rule is what lets small leaves merge the far field as
// widely as large ones: with the height rule alone, block 16's exact nodes were a quarter
// of block 32's area, its far field stayed 4x finer, and over a whole 16385^2 DEM it drew
// 1.5x the triangles of block 32 (benchmarks-core.md, session 8).
constexpr int kExactMergedHeight = 4;
constexpr int kExactMergedQuads = 512;

struct ErrorTable
{
  int levels = 0; // entries per block (top level of the largest block + 1)
  // ownError[b * levels + m]: error of block b at level m with its own edges (the level, or
  // every sample on a side that is always at full resolution at m; a side that may be
  // either, Quadtree::sideAtFullResolutionAt, counts both ways); made monotone
  // (non-decreasing) in m; +inf for levels that are invalid for the block, and for the
  // levels of a block with nodata that draw no fewer triangles than a finer allowed one
  // (its cells may outnumber a finer level's, HoleCells.h).
  std::vector<float> ownError;
  // Exact (not monotone) error of the same configuration, for reporting certified bounds.
  std::vector<float> ownErrorExact;
  // stripError[((b * 4 + side) * pairs) + pairIndex(m, n)] for ring levels m < n: error of
  // the side strip of block b at level m when the edge is sampled at level n. Made monotone
  // in n. Zero where unused: sides always at full resolution at m (the block or its
  // neighbour holds nodata and b does not follow the edge levels there,
  // Quadtree::followsEdgeLevels) have no coarser edge, and their strip is part of ownError.
  std::vector<float> stripError;
  int pairs = 0; // levels * (levels - 1) / 2
  // mergedError[node]: error of quadtree node `node` drawn whole (Tessellate.h, merged
  // nodes: the fan over its perimeter): exact where mergedErrorIsExact, the node's height
  // range (a bound) elsewhere; +inf for leaves, nodes that are not mergeable and nodes
  // over nodata.
  std::vector<float> mergedError;
  // The fan morph's exact errors of each node that merges by it (FanMorph.h, fanMorphable;
  // +inf for the others): fanResidual[node], how far its fan is from its children at their
  // coarsest with their corners on the fan; fanMovedError[node], those moved children's
  // error; fanChildrenError[node], the children's own.
  std::vector<float> fanResidual, fanMovedError, fanChildrenError;
  // Coarse perimeters of merged nodes (CoarsePerimeter.h): node n's entries, one per
  // perimeter depth 0 to its height - 1, start at perimeterFirst[n] (nodes + 1 offsets,
  // derived from the quadtree, not stored in cache files). perimeterError: the bound of its
  // fan's error at that depth, whatever the neighbours add; perimeterPop: of its change
  // from the full perimeter's fan; +inf for nodes whose perimeter stays full.
  std::vector<uint32_t> perimeterFirst;
  std::vector<float> perimeterError, perimeterPop;
  // cellTriangles[b * levels + m]: triangles of block b with nodata at ring level m that
  // depend on the level alone, those that nodata drops left out: at level 0 every quad
  // (drawnTriangleCount), above it its cells (HoleCells.h) and where they leave
  // the border rows to side strips, the strips' steps along the inner ring
  // (holeCellsTriangleCount); 0 elsewhere.
  // Triangle budgets ask for counts at every refinement step, and classifying the cells
  // each time made a budgeted frame over Rainier 10x slower. Empty when the DEM has no
  // nodata. Derived from the quadtree (fillCellTriangles), not stored in cache files.
  std::vector<uint32_t> cellTriangles;

  static int pairIndex(int m, int n) { return n * (n - 1) / 2 + m; } // m < n
  float own(int block, int m) const { return ownError[static_cast<std::size_t>(block) * levels + m]; }
  float ownExact(int block, int m) const
  {
    return ownErrorExact[static_cast<std::size_t>(block) * levels + m];
  }
  // Inline: the selection reads it for every strip of every drawn block, every frame.
  float strip(int block, int side, int m, int n) const
  {
    return stripError[(static_cast<std::size_t>(block) * 4 + side) * pairs + pairIndex(m, n)];
  }
};

// Whether mergedError[node] is the exact error of the node's fan (kExactMergedHeight,
// kExactMergedQuads) rather than a bound.
bool mergedErrorIsExact(const Quadtree& qt, int node);

// Fills table.cellTriangles for the quadtree's blocks with nodata (table.levels set), on up
// to `threads` threads (0 = the hardware's): the one writer of those counts.
// buildErrorTable calls it before the errors (the counts decide which levels are allowed);
// a table read from a cache file needs it too.
void fillCellTriangles(const Quadtree& qt, ErrorTable& table, int threads = 0);

// Builds the table with up to `threads` worker threads (0 = hardware concurrency).
// `progress`, when given, is called with the fraction of blocks done, from the calling
// thread only (the workers count, the caller reports).
ErrorTable buildErrorTable(const Heightfield& hf, const Quadtree& qt, int threads = 0,
  const std::function<void(double)>& progress = nullptr);

} // namespace gmm
