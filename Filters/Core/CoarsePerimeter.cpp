// Coarse perimeters of merged nodes (CoarsePerimeter.h): which nodes may have one, their
// exact tables, and the depth a node drawn whole takes.
#include "CoarsePerimeter.h"

#include "RasterError.h"
#include "Tessellate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace gmm
{

bool perimeterCoarsens(const Quadtree& qt, int node)
{
  return mergeableNode(qt, node) && mergedErrorIsExact(qt, node) && qt.nodeClearOfNodata(node);
}

void perimeterOffsets(const Quadtree& qt, std::vector<uint32_t>& first)
{
  first.resize(qt.nodes.size() + 1);
  uint32_t at = 0;
  for (std::size_t n = 0; n < qt.nodes.size(); ++n)
  {
    first[n] = at;
    at += static_cast<uint32_t>(qt.nodes[n].height);
  }
  first[qt.nodes.size()] = at;
}

namespace
{
// One side's partitions as an implicit binary tree (heap order, root 1, children 2k and
// 2k + 1 down to depth `depths`): each entry a segment of the side, the fan's triangle from
// `centre` over it. A segment of one band is its own children, so every depth has an entry
// wherever a sample's ray leaves. `vertical`: the side is a column of samples at `line`.
using Segment = PerimeterSegment;

void buildSegments(const std::vector<int>& start, int b0, int b1, const double* heights, int depths,
  GridPoint centre, bool vertical, int line, std::vector<Segment>& tree)
{
  tree.assign(std::size_t{ 2 } << depths, Segment());
  struct Range
  {
    int lo, hi;
  };
  std::vector<Range> range(tree.size());
  range[1] = { b0, b1 };
  auto point = [&](int k) { return vertical ? GridPoint{ line, start[k] } : GridPoint{ start[k], line }; };
  for (std::size_t k = 1; k < tree.size(); ++k)
  {
    const Range r = range[k];
    const int m = r.hi - r.lo > 1 ? splitBand(r.lo, r.hi) : r.hi;
    Segment& g = tree[k];
    g.a = point(r.lo);
    g.b = point(r.hi);
    g.ha = heights[r.lo - b0];
    g.hb = heights[r.hi - b0];
    // The triangle (centre, a, b) as rasterising weighs it: integer barycentric weights.
    const int64_t area =
      int64_t(g.a.i - centre.i) * (g.b.j - centre.j) - int64_t(g.a.j - centre.j) * (g.b.i - centre.i);
    g.sign = area >= 0 ? 1 : -1;
    g.inv = area != 0 ? 1.0 / std::abs(static_cast<double>(area)) : 0.0;
    g.split = start[m];
    if (2 * k + 1 < tree.size())
    {
      range[2 * k] = r.hi - r.lo > 1 ? Range{ r.lo, m } : r;
      range[2 * k + 1] = r.hi - r.lo > 1 ? Range{ m, r.hi } : r;
    }
  }
}

// The height of triangle (c, g.a, g.b) at (i, j), with c's height 0: its integer
// barycentric weights, so that a plane is reproduced as rasterising does.
inline double heightOn(const Segment& g, GridPoint c, int i, int j)
{
  const int64_t wa = g.sign * (int64_t(g.b.i - i) * (c.j - j) - int64_t(g.b.j - j) * (c.i - i));
  const int64_t wb = g.sign * (int64_t(c.i - i) * (g.a.j - j) - int64_t(c.j - j) * (g.a.i - i));
  return (wa * g.ha + wb * g.hb) * g.inv;
}
} // namespace

void coarsePerimeterErrors(const Heightfield& hf, const Quadtree& qt, int node, CoarsePerimeterScratch& scratch,
  float* error, float* pop)
{
  const QuadtreeNode& n = qt.nodes[node];
  const int depths = n.height;
  if (!perimeterCoarsens(qt, node))
  {
    std::fill(error, error + depths, std::numeric_limits<float>::infinity());
    std::fill(pop, pop + depths, std::numeric_limits<float>::infinity());
    return;
  }
  const int i0 = qt.colStart[n.colBegin], i1 = qt.colStart[n.colEnd];
  const int j0 = qt.rowStart[n.rowBegin], j1 = qt.rowStart[n.rowEnd];
  // Heights relative to the fan's centre sample: errors from differences, as the table's.
  const GridPoint centre = mergedCentre(qt, node);
  const double z0 = hf.height(centre.i, centre.j);
  // The heights at the band boundaries along each side (less z0): south, north (by column
  // band), west, east (by row band), and each side's partitions down to the full perimeter
  // (depth `depths`: single bands).
  const int cols = n.colEnd - n.colBegin, rows = n.rowEnd - n.rowBegin;
  std::vector<double>& border = scratch.borderHeights;
  border.resize(2 * static_cast<std::size_t>(cols + 1) + 2 * static_cast<std::size_t>(rows + 1));
  double* south = border.data();
  double* north = south + cols + 1;
  double* west = north + cols + 1;
  double* east = west + rows + 1;
  for (int c = 0; c <= cols; ++c)
  {
    south[c] = hf.height(qt.colStart[n.colBegin + c], j0) - z0;
    north[c] = hf.height(qt.colStart[n.colBegin + c], j1) - z0;
  }
  for (int r = 0; r <= rows; ++r)
  {
    west[r] = hf.height(i0, qt.rowStart[n.rowBegin + r]) - z0;
    east[r] = hf.height(i1, qt.rowStart[n.rowBegin + r]) - z0;
  }
  std::array<std::vector<Segment>, 4>& tree = scratch.sides;
  buildSegments(qt.colStart, n.colBegin, n.colEnd, south, depths, centre, false, j0, tree[South]);
  buildSegments(qt.colStart, n.colBegin, n.colEnd, north, depths, centre, false, j1, tree[North]);
  buildSegments(qt.rowStart, n.rowBegin, n.rowEnd, west, depths, centre, true, i0, tree[West]);
  buildSegments(qt.rowStart, n.rowBegin, n.rowEnd, east, depths, centre, true, i1, tree[East]);
  // One pass over the node's samples for every depth: a fan's triangle is linear along the
  // ray from the centre, so a sample's height on the fan of any perimeter is the centre's
  // and the perimeter's where the ray leaves the node, on the segment of that partition
  // (fanSurfaceHeight's rule). Per depth, the largest |fan - sample| and |fan - full fan|.
  std::vector<double>& worst = scratch.worst;
  worst.assign(2 * static_cast<std::size_t>(depths), 0.0);
  double* e = worst.data();
  double* p = e + depths;
  std::vector<double>& at = scratch.depthHeights;
  at.resize(static_cast<std::size_t>(depths) + 1);
  double fullError = 0.0;
  const double inf = std::numeric_limits<double>::infinity();
  // Where the ray through column i leaves through the east or west side, in units of its
  // step (inf on the centre's column): per column once, not per sample.
  std::vector<double>& exitX = scratch.exitX;
  exitX.resize(static_cast<std::size_t>(i1 - i0) + 1);
  for (int i = i0; i <= i1; ++i)
  {
    const int dx = i - centre.i;
    exitX[i - i0] = dx > 0 ? double(i1 - centre.i) / dx : dx < 0 ? double(i0 - centre.i) / dx : inf;
  }
  for (int j = j0; j <= j1; ++j)
  {
    const float* row = hf.heights() + hf.index(i0, j);
    const int dy = j - centre.j;
    const double sy = dy > 0 ? double(j1 - centre.j) / dy : dy < 0 ? double(j0 - centre.j) / dy : inf;
    for (int i = i0; i <= i1; ++i)
    {
      const double sample = row[i - i0] - z0;
      const int dx = i - centre.i;
      if (dx == 0 && dy == 0)
      {
        continue; // the apex of every fan, at its own height
      }
      const double sx = exitX[i - i0];
      const bool vertical = sx <= sy; // leaves through the east or west side
      // Where the ray leaves picks each depth's segment (on a tie both give the same
      // height: the sample is on their common edge); the height is the triangle's.
      const double s = std::min(sx, sy);
      const double along = vertical ? centre.j + s * dy : centre.i + s * dx;
      const Segment* side = tree[vertical ? (dx > 0 ? East : West) : (dy > 0 ? North : South)].data();
      std::size_t k = 1;
      for (int d = 0; d <= depths; ++d)
      {
        const Segment& g = side[k];
        at[d] = heightOn(g, centre, i, j);
        k = 2 * k + (along >= g.split ? 1 : 0);
      }
      fullError = std::max(fullError, std::abs(at[depths] - sample));
      for (int d = 0; d < depths; ++d)
      {
        e[d] = std::max(e[d], std::abs(at[d] - sample));
        p[d] = std::max(p[d], std::abs(at[d] - at[depths]));
      }
    }
  }
  // Each depth's largest over it and every finer one (the full perimeter's error included).
  double cumError = fullError, cumPop = 0.0;
  for (int d = depths - 1; d >= 0; --d)
  {
    cumError = std::max(cumError, e[d]);
    cumPop = std::max(cumPop, p[d]);
    error[d] = roundUpToFloat(cumError);
    pop[d] = roundUpToFloat(cumPop);
  }
}

float mergedErrorAt(const Quadtree& qt, const ErrorTable& table, int node, int depth)
{
  return depth < qt.nodes[node].height ? table.perimeterError[table.perimeterFirst[node] + depth]
                                       : table.mergedError[node];
}

int coarsestPerimeterDepth(const Quadtree& qt, const ErrorTable& table, int node, double budget, double popBudget)
{
  const int depths = qt.nodes[node].height;
  const uint32_t first = table.perimeterFirst[node];
  for (int d = 0; d < depths; ++d)
  {
    if (table.perimeterError[first + d] <= budget && table.perimeterPop[first + d] <= popBudget)
    {
      return d;
    }
  }
  return kFullPerimeter;
}

} // namespace gmm
