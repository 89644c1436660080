// Vertical error of drawn shapes over the full-resolution samples they cover: triangles,
// a block's inner grid, a side strip and the polylines along its two lines. The error of a
// sample is its vertical distance to the drawn surface above/below it; a shape's error is
// the maximum over its samples (edges included). Errors are computed in double from height
// differences, so a constant height offset gives the very same value and a plane exactly
// 0, and rounded up to float (roundUpToFloat), never below the exact value. The error
// table (ErrorTable.h) is built from these.
#pragma once

#include "Heightfield.h"
#include "Tessellate.h"

#include <vector>

namespace gmm
{

// A double error as the float the tables store: rounded up, so that a certified bound is
// never a hair below the measured error. +inf only for heights validateHeightfield refuses
// (heights are limited to +-kMaxHeight, so no real error overflows to the +inf that marks
// a level as not allowed).
float roundUpToFloat(double e);

// Maximum vertical error of the samples covered by a list of triangles (grid points), the
// building block of the table; exposed for tests. strictNodata: a nodata vertex or covered
// nodata sample is +inf (the triangle would draw over a hole); otherwise a triangle
// touching nodata is an accepted full-resolution hole and counts 0.
float trianglesError(const Heightfield& hf, const std::vector<GridTriangle>& tris, bool strictNodata);

// Error of the inner grid of a ring block at a level > 0 (what Tessellate's drawInnerGrid
// emits over inner columns C[1..k-1] and rows R[1..L-1], C and R from edgeSamples), with
// every sample evaluated once in a direct walk over the cells: the same value as
// rasterising those triangles (up to the rounding of a sample on a cell border, which both
// cells interpolate alike), at a fraction of the cost. Nodata anywhere gives +inf.
float innerAreaError(const Heightfield& hf, const std::vector<int>& C, const std::vector<int>& R);

// Error of a polyline of consecutive points along one row or one column, each segment
// interpolating linearly between its end samples: what any triangle with that segment as
// an edge draws at the samples on it. Nodata anywhere on it, ends included, gives +inf.
float polylineError(const Heightfield& hf, const std::vector<GridPoint>& points);

// The largest distance of the samples along `side` of `block` from the side's polyline at
// `level` (its samples at that level's step, edgeSamples): the error of that edge line, and
// how far an edge vertex moves toward that polyline, at most (+inf with nodata on the side).
float sidePolylineError(const Heightfield& hf, const Quadtree& qt, int block, int side, int level,
  EmitScratch& scratch);

// A block side whose vertices are drawn on a coarser polyline (a glided edge, EdgeHeights.h):
// row j = line (rows) or column i = line, its vertices at the polyline through the line's
// samples at `level` from `first` to `last` (its ends: the block's corners).
struct GlidedLine
{
  bool rows;
  int line, first, last, level;
};

// Error of a side strip's triangles (Tessellate.h, sidePolylines) at the samples strictly
// between its two lines, rows j = lineA and j = lineB (rows) or columns i = lineA and
// i = lineB: the samples on the lines are the polylines' (polylineError), measured once per
// line instead of once per triangle that touches it. The strip's error is the largest of
// the three. Nodata is strict (+inf). With `glide`, the vertices on that line are drawn on
// its polyline (a glided edge's).
float stripInteriorError(const Heightfield& hf, const std::vector<GridTriangle>& tris, bool rows,
  int lineA, int lineB, const GlidedLine* glide = nullptr);

} // namespace gmm
