// Coarse perimeters of merged nodes (CoarsePerimeter.h): which nodes may have one, their
// exact tables, and the depth a node drawn whole takes.
#include "CoarsePerimeter.h"

#include "FanRaster.h"
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
  if (!mergeableNode(qt, node) || !mergedErrorIsExact(qt, node))
  {
    return false;
  }
  const QuadtreeNode& n = qt.nodes[node];
  for (int r = n.rowBegin; r < n.rowEnd; ++r)
  {
    for (int c = n.colBegin; c < n.colEnd; ++c)
    {
      const int b = qt.blockIndex(c, r);
      if (qt.blockHasNodata[b] || qt.anySideAtFullResolution(b))
      {
        return false;
      }
    }
  }
  return true;
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
  const int width = i1 - i0 + 1;
  // Heights relative to the fan's centre sample: errors from differences, as the table's.
  const GridPoint centre = mergedCentre(qt, node);
  const double z0 = hf.height(centre.i, centre.j);
  auto own = [&](GridPoint p) { return hf.height(p.i, p.j) - z0; };
  std::vector<double>& full = scratch.fan;
  full.resize(static_cast<std::size_t>(width) * (j1 - j0 + 1)); // every sample is written
  std::vector<GridTriangle>& tris = scratch.triangles;
  tris.clear();
  emitMergedNodeGrid(qt, node, tris);
  double fullError = 0.0;
  for (const GridTriangle& t : tris)
  {
    const std::array<double, 3> h{ own(t.v[0]), own(t.v[1]), own(t.v[2]) };
    rasteriseFanTriangle(t, h, h, i0, j0, width, [&](int i, int j, std::size_t s, double f, double) {
      full[s] = f;
      fullError = std::max(fullError, std::abs(f - (hf.height(i, j) - z0)));
    });
  }
  // From the finest depth down, each depth's largest over it and every finer one.
  double e = fullError, p = 0.0;
  for (int d = depths - 1; d >= 0; --d)
  {
    tris.clear();
    emitCoarseMergedNodeGrid(qt, node, d, tris, scratch.perimeter);
    for (const GridTriangle& t : tris)
    {
      const std::array<double, 3> h{ own(t.v[0]), own(t.v[1]), own(t.v[2]) };
      rasteriseFanTriangle(t, h, h, i0, j0, width, [&](int i, int j, std::size_t s, double f, double) {
        e = std::max(e, std::abs(f - (hf.height(i, j) - z0)));
        p = std::max(p, std::abs(f - full[s]));
      });
    }
    error[d] = roundUpToFloat(e);
    pop[d] = roundUpToFloat(p);
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
