// The grid's small vocabulary, shared by tessellation and the cells around nodata: block
// sides, sample positions and triangles in (column, row) space.
#pragma once

namespace gmm
{

enum Side
{
  South = 0, // j = first row of the block (low y when dy > 0)
  East = 1,  // i = last column
  North = 2, // j = last row
  West = 3   // i = first column
};

struct GridPoint
{
  int i, j; // column, row
};

// One triangle as grid points, counter-clockwise in (i, j) grid space.
struct GridTriangle
{
  GridPoint v[3];
};

} // namespace gmm
