// Coarse perimeters: far terrain in few triangles. A merged node's fan (Tessellate.h) passes
// through every block corner on its border, so that any neighbour meets it; with small
// blocks that is most of a far field's triangles (over N48W125 at block 8, 82 000 of a
// frame's 90 000). A merged node whose error allows it draws its fan to the points of a
// coarser partition of its border instead (its perimeter depth d: its band ranges split d
// times by splitBand), plus whatever points the drawn neighbours across need
// (coarsePerimeter, Tessellate.h), so that both sides of a line agree.
//
// Exact tables (per node and depth, ErrorTable::perimeterError and perimeterPop): a drawn
// fan's pieces along a side are ranges of the bands' splitBand tree at depth d or deeper
// (the union of two partitions into ranges of one tree is one), and a fan triangle's error
// depends only on its own three vertices, so the largest error over depths d and finer,
// and the largest change from the full perimeter's fan over the same depths, bound what any
// frame draws at depth d, whatever its neighbours add.
//
// Selection (SelectNodes.h): a node drawn whole takes the coarsest depth whose error fits
// its budget; with geomorphing it also changes the surface by at most kPerimeterPopPixels
// from its full perimeter, so that a depth change, the appearing or leaving point of a
// neighbour's, or a merge moves nothing by more than the pop bound.
#pragma once

#include "ErrorTable.h"
#include "GridTypes.h"
#include "Heightfield.h"
#include "Quadtree.h"

#include <array>
#include <cstdint>
#include <vector>

namespace gmm
{

// A merged node's perimeter depth when it has every block corner (mergedPerimeter): any
// depth at or above the node's height is that.
constexpr int8_t kFullPerimeter = 127;

// With geomorphing, a perimeter is coarser than full only where its fan is within this many
// pixels of the full perimeter's fan everywhere: two frames' perimeters then differ by at
// most twice this, within the 0.3 px a frame. A fan morph's merge (FanMorph.h)
// already spends up to kMergePopPixels, so such a node coarsens only once its residual
// projects within this too.
constexpr double kPerimeterPopPixels = 0.15;

// Whether `node`'s perimeter may be coarser than full: mergeable, its fan's error exact
// (mergedErrorIsExact), no nodata below it and no side at full resolution on its blocks.
bool perimeterCoarsens(const Quadtree& qt, int node);

// ErrorTable::perimeterFirst for the quadtree: node n's entries (depths 0 to its height - 1)
// start at first[n]; first has nodes + 1 entries. Derived from the quadtree, not stored.
void perimeterOffsets(const Quadtree& qt, std::vector<uint32_t>& first);

// A segment of a node's side in one of its partitions: its ends and their heights (less the
// centre's), the fan triangle's orientation and 1 / |its doubled area|, and where along the
// side its two halves part.
struct PerimeterSegment
{
  GridPoint a{ 0, 0 }, b{ 0, 0 };
  double ha = 0.0, hb = 0.0, inv = 0.0, split = 0.0;
  int64_t sign = 1;
};

// Buffers coarsePerimeterErrors reuses from node to node.
struct CoarsePerimeterScratch
{
  std::vector<double> worst, depthHeights, borderHeights, exitX;
  std::array<std::vector<PerimeterSegment>, 4> sides; // per side (Side order), its partitions
};

// The exact tables of `node`, its height entries each (depth 0 first): error[d], the
// largest |fan - sample| over the fans at depths d and finer (the full perimeter's
// included), pop[d], the largest |fan - full perimeter's fan| over the same (heights in
// stored units, rounded up to float); +inf where !perimeterCoarsens.
void coarsePerimeterErrors(const Heightfield& hf, const Quadtree& qt, int node, CoarsePerimeterScratch& scratch,
  float* error, float* pop);

// The error of `node` drawn whole at perimeter depth `depth`: the table's bound at that depth, or
// its merged error at full depth.
float mergedErrorAt(const Quadtree& qt, const ErrorTable& table, int node, int depth);

// The coarsest perimeter depth of merged `node` whose error fits `budget` and, when
// `popBudget` is finite, whose change from the full perimeter fits that too;
// kFullPerimeter when none does.
int coarsestPerimeterDepth(const Quadtree& qt, const ErrorTable& table, int node, double budget, double popBudget);

} // namespace gmm
