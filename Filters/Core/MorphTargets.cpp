// Where a morphing vertex goes, and the height it is drawn at (Morph.h: blockVertexTarget,
// morphTarget, morphedHeight), as the mapper's vertex shader mirrors it line by line.
#include "Morph.h"

#include "EdgeHeights.h"
#include "Levels.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace gmm
{

namespace
{

// Height of block rectangle [i0, i1] x [j0, j1] drawn at `level`, at the interior sample
// (i, j): the cell of the grid edgeSamples(level) x edgeSamples(level) that holds it, split
// as Tessellate splits it (see Morph.h), its corners' heights from cornerAt(i, j).
template <typename CornerAt>
double blockSurfaceAt(int i0, int i1, int j0, int j1, int level, bool oneQuadAnti, int i, int j, CornerAt cornerAt)
{
  const long long step = 1LL << level;
  const long long u = (i - i0) / step, v = (j - j0) / step;
  const int ia = static_cast<int>(i0 + u * step), ja = static_cast<int>(j0 + v * step);
  const int ib = static_cast<int>(std::min<long long>(ia + step, i1));
  const int jb = static_cast<int>(std::min<long long>(ja + step, j1));
  const long long k = (i1 - i0 + step - 1) / step, L = (j1 - j0 + step - 1) / step; // cells per side
  const bool ring = blockShape(i1 - i0, j1 - j0, level) == BlockShape::Ring;
  const bool anti = ring ? ringCellAntiDiagonal(static_cast<int>(u), static_cast<int>(v), static_cast<int>(k),
                             static_cast<int>(L))
                        : oneQuadAnti;
  const double fx = static_cast<double>(i - ia) / static_cast<double>(ib - ia);
  const double fy = static_cast<double>(j - ja) / static_cast<double>(jb - ja);
  return splitQuadHeight(cornerAt(ia, ja), cornerAt(ib, ja), cornerAt(ia, jb), cornerAt(ib, jb), fx, fy, anti);
}

} // namespace

double blockVertexTarget(const Heightfield& hf, const Quadtree& qt, int block, int target,
  const std::array<int, 4>& edgeTarget, const std::array<int, 4>& edgeLevel, int i, int j,
  const std::array<double, 4>& edgeFactor)
{
  const int c = block % qt.blockCols, r = block / qt.blockCols;
  const int i0 = qt.colStart[c], i1 = qt.colStart[c + 1], j0 = qt.rowStart[r], j1 = qt.rowStart[r + 1];
  // A sample on side s at the edge's height under factor edgeFactor[s] (its base height, or
  // that far toward the polyline at the edge's target).
  auto edgeAt = [&](int side, int ei, int ej, double t) {
    const double base = sideBaseHeight(hf, i0, i1, j0, j1, edgeLevel, ei, ej);
    if (edgeTarget[side] < 0 || !(t > 0.0))
    {
      return base;
    }
    const double to = sidePolylineAt(hf, i0, i1, j0, j1, side, edgeTarget[side], ei, ej);
    return t >= 1.0 ? to : base + t * (to - base);
  };
  const int side = borderSideOf(i0, i1, j0, j1, i, j);
  if (side >= 0)
  {
    return edgeAt(side, i, j, 1.0);
  }
  const bool corner = (i == i0 || i == i1) && (j == j0 || j == j1);
  if (target < 0 || corner)
  {
    return hf.height(i, j); // a block corner is on every level
  }
  return blockSurfaceAt(i0, i1, j0, j1, target, oneQuadAntiDiagonal(qt, block), i, j, [&](int ci, int cj) {
    const int s = borderSideOf(i0, i1, j0, j1, ci, cj);
    return s < 0 ? static_cast<double>(hf.height(ci, cj)) : edgeAt(s, ci, cj, edgeFactor[s]);
  });
}

namespace
{
// The edge levels of block b's four sides in a frame (-1 where an edge is not drawn: no
// vertex of b lies on it then).
std::array<int, 4> edgeLevelsOf(const std::array<const MorphEdge*, 4>& edges)
{
  return { edges[0]->level, edges[1]->level, edges[2]->level, edges[3]->level };
}

// Sample (i, j)'s block, its base height there (sideBaseHeight) and its target and factor.
struct VertexMorph
{
  double base = 0.0, target = 0.0, t = 0.0;
};

VertexMorph vertexMorph(const Heightfield& hf, const Quadtree& qt, const std::vector<int8_t>& levels,
  const MorphFrame& frame, int i, int j)
{
  const int c = bandOfSample(qt.colStart, i), r = bandOfSample(qt.rowStart, j);
  const int b = qt.blockIndex(c, r);
  const std::array<const MorphEdge*, 4> edges = blockEdges(qt, frame, b);
  const int i0 = qt.colStart[c], i1 = qt.colStart[c + 1], j0 = qt.rowStart[r], j1 = qt.rowStart[r + 1];
  const int side = borderSideOf(i0, i1, j0, j1, i, j);
  const bool onV = i == i0 || i == i1, onH = j == j0 || j == j1;
  const std::array<int, 4> edgeLevel = edgeLevelsOf(edges);
  VertexMorph v;
  v.base = sideBaseHeight(hf, i0, i1, j0, j1, edgeLevel, i, j);
  if (onV && onH) // a block corner: moves only onto a merging node's fan (FanMorph.h)
  {
    const std::size_t k = static_cast<std::size_t>(j == j0 ? r : r + 1) * (qt.blockCols + 1) + (i == i0 ? c : c + 1);
    const bool moving = k < frame.cornerT.size() && frame.cornerT[k] > 0.0f;
    v.t = moving ? frame.cornerT[k] : 0.0;
    v.target = moving ? static_cast<double>(frame.cornerTarget[k]) : v.base;
    return v;
  }
  if (side >= 0) // on one edge
  {
    v.t = edges[side]->t;
  }
  else if (!onV && !onH && levels[b] >= 0)
  {
    v.t = frame.blockT[b];
  }
  const bool interior = !onV && !onH;
  const int target = interior && levels[b] >= 0 ? frame.blockTarget[b] : -1;
  v.target = blockVertexTarget(hf, qt, b, target,
    { edges[0]->target, edges[1]->target, edges[2]->target, edges[3]->target }, edgeLevel, i, j,
    { edges[0]->t, edges[1]->t, edges[2]->t, edges[3]->t });
  return v;
}
} // namespace

double morphTarget(const Heightfield& hf, const Quadtree& qt, const std::vector<int8_t>& levels,
  const MorphFrame& frame, int i, int j, double* factorOut)
{
  const VertexMorph v = vertexMorph(hf, qt, levels, frame, i, j);
  *factorOut = v.t;
  return v.target;
}

double morphedHeight(const Heightfield& hf, const Quadtree& qt, const std::vector<int8_t>& levels,
  const MorphFrame& frame, int i, int j)
{
  const VertexMorph v = vertexMorph(hf, qt, levels, frame, i, j);
  // t == 0 must give the base exactly, even where the target is nodata (NaN).
  return v.t > 0.0 && std::isfinite(v.target) ? v.base + v.t * (v.target - v.base) : v.base;
}

} // namespace gmm
