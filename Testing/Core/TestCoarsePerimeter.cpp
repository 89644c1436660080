// Coarse perimeters of merged nodes (CoarsePerimeter.h): a node drawn whole fans to the
// points of a coarser partition of its border, plus the points its neighbours across need.
// The tables are checked against fans built here from the quadtree's bands alone and
// rasterised sample by sample; the frames for cracks (checkMesh), and each coarse fan as
// drawn, with whatever its neighbours added, against its table's bound, measured here.
#include "CoarsePerimeter.h"
#include "CoreTestUtil.h"
#include "Engine.h"
#include "StressUtil.h"
#include "Tessellate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <set>
#include <string>
#include <vector>

using namespace gmmtest;

namespace
{
struct Point
{
  int i, j;
};
using Triangle = std::array<Point, 3>;

// Where a range of bands [b0, b1) splits: after the largest power of two below its count.
int splitAt(int b0, int b1)
{
  int half = 1;
  while (2 * half < b1 - b0)
    half *= 2;
  return b0 + half;
}

// The band boundaries that `depth` halvings of [b0, b1) give, ends included.
void partition(int b0, int b1, int depth, std::set<int>& out)
{
  out.insert(b0);
  out.insert(b1);
  if (depth == 0 || b1 - b0 < 2)
    return;
  const int m = splitAt(b0, b1);
  partition(b0, m, depth - 1, out);
  partition(m, b1, depth - 1, out);
}

// Node `node`'s fan to the band boundaries of its depth-`depth` partition, from the point
// where its bands split, counter-clockwise.
std::vector<Triangle> fanAtDepth(const gmm::Quadtree& qt, int node, int depth)
{
  const gmm::QuadtreeNode& n = qt.nodes[node];
  std::set<int> cols, rows;
  partition(n.colBegin, n.colEnd, depth, cols);
  partition(n.rowBegin, n.rowEnd, depth, rows);
  const int i0 = qt.colStart[n.colBegin], i1 = qt.colStart[n.colEnd];
  const int j0 = qt.rowStart[n.rowBegin], j1 = qt.rowStart[n.rowEnd];
  std::vector<Point> ring;
  for (auto c = cols.begin(); std::next(c) != cols.end(); ++c)
    ring.push_back({ qt.colStart[*c], j0 });
  for (auto r = rows.begin(); std::next(r) != rows.end(); ++r)
    ring.push_back({ i1, qt.rowStart[*r] });
  for (auto c = cols.rbegin(); std::next(c) != cols.rend(); ++c)
    ring.push_back({ qt.colStart[*c], j1 });
  for (auto r = rows.rbegin(); std::next(r) != rows.rend(); ++r)
    ring.push_back({ i0, qt.rowStart[*r] });
  const Point centre{ qt.colStart[splitAt(n.colBegin, n.colEnd)], qt.rowStart[splitAt(n.rowBegin, n.rowEnd)] };
  std::vector<Triangle> fan;
  for (std::size_t k = 0; k < ring.size(); ++k)
    fan.push_back({ centre, ring[k], ring[(k + 1) % ring.size()] });
  return fan;
}

// The heights the triangles interpolate at every sample of the rectangle [i0, i1] x [j0, j1]
// (row by row; NaN where none covers it).
std::vector<double> paint(const gmm::Heightfield& hf, const std::vector<Triangle>& tris, int i0, int j0, int i1,
  int j1)
{
  const int width = i1 - i0 + 1;
  std::vector<double> out(static_cast<std::size_t>(width) * (j1 - j0 + 1), std::nan(""));
  for (const Triangle& t : tris)
    paintTriangle(t[0].i, t[0].j, t[1].i, t[1].j, t[2].i, t[2].j, hf.height(t[0].i, t[0].j),
      hf.height(t[1].i, t[1].j), hf.height(t[2].i, t[2].j),
      [&](int i, int j, double h) { out[static_cast<std::size_t>(j - j0) * width + (i - i0)] = h; });
  return out;
}

// Largest |a - b| over the rectangle's samples; NaN in either (an uncovered sample) is +inf.
double largestDifference(const std::vector<double>& a, const std::vector<double>& b)
{
  double worst = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k)
    worst = std::max(worst, std::isnan(a[k]) || std::isnan(b[k]) ? INFINITY : std::fabs(a[k] - b[k]));
  return worst;
}

std::vector<double> samplesOf(const gmm::Heightfield& hf, int i0, int j0, int i1, int j1)
{
  std::vector<double> out;
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i)
      out.push_back(hf.height(i, j));
  return out;
}
} // namespace

// Every node's error and change from its full perimeter at each depth, as the table holds
// them: the largest over that depth and every finer one (the full perimeter's error
// included), measured on fans built here.
TEST(CoarsePerimeter, TablesMatchFansBuiltByHand)
{
  Rng rng(29);
  const int sizes[][3] = { { 129, 129, 8 }, { 131, 97, 8 }, { 97, 161, 4 }, { 257, 65, 16 } };
  int checked = 0, coarser = 0;
  for (auto& s : sizes)
  {
    gmm::Engine e;
    ASSERT_EQ(e.setHeightfield(roughTerrain(s[0], s[1], rng), s[2], 1), "");
    const gmm::Heightfield& hf = e.heightfield();
    const gmm::Quadtree& qt = e.quadtree();
    const gmm::ErrorTable& table = e.terrain()->table;
    for (int node = 0; node < static_cast<int>(qt.nodes.size()); ++node)
    {
      const gmm::QuadtreeNode& n = qt.nodes[node];
      if (n.colEnd - n.colBegin < 2 || n.rowEnd - n.rowBegin < 2)
        continue; // not drawn whole
      ASSERT_TRUE(gmm::perimeterCoarsens(qt, node)) << "no nodata here, and every node's fan is exact";
      const int i0 = qt.colStart[n.colBegin], i1 = qt.colStart[n.colEnd];
      const int j0 = qt.rowStart[n.rowBegin], j1 = qt.rowStart[n.rowEnd];
      const std::vector<double> heights = samplesOf(hf, i0, j0, i1, j1);
      const std::vector<double> full = paint(hf, fanAtDepth(qt, node, n.height), i0, j0, i1, j1);
      double error = largestDifference(full, heights), change = 0.0;
      for (int d = n.height - 1; d >= 0; --d)
      {
        const std::vector<double> fan = paint(hf, fanAtDepth(qt, node, d), i0, j0, i1, j1);
        error = std::max(error, largestDifference(fan, heights));
        change = std::max(change, largestDifference(fan, full));
        const float te = table.perimeterError[table.perimeterFirst[node] + d];
        const float tp = table.perimeterPop[table.perimeterFirst[node] + d];
        EXPECT_GE(te, error * (1 - 1e-6) - 1e-9) << "node " << node << " depth " << d;
        EXPECT_LE(te, error * (1 + 1e-6) + 1e-6) << "node " << node << " depth " << d;
        EXPECT_GE(tp, change * (1 - 1e-6) - 1e-9) << "node " << node << " depth " << d;
        EXPECT_LE(tp, change * (1 + 1e-6) + 1e-6) << "node " << node << " depth " << d;
        coarser += change > 0.0;
        ++checked;
      }
    }
  }
  std::printf("[ coarse perimeter ] %d node depths checked, %d differing from the full perimeter\n", checked,
    coarser);
  EXPECT_GT(checked, 200);
  EXPECT_GT(coarser, checked / 2);
}

// Frames over rough terrain, with and without geomorphing: no crack whatever the depths of
// neighbouring merged nodes, and every coarse fan as drawn (its own partition and the
// points its neighbours added) within its table's bound at its depth, measured here over
// its samples.
TEST(CoarsePerimeter, DrawnFansMeetTheirNeighboursWithinTheirBounds)
{
  Rng rng(31);
  int frames = 0, coarseFans = 0, widened = 0, coarseBesideCoarse = 0;
  for (int trial = 0; trial < 6; ++trial)
  {
    const int nx = randInt(rng, 120, 260), ny = randInt(rng, 120, 260);
    gmm::Engine e;
    ASSERT_EQ(e.setHeightfield(roughTerrain(nx, ny, rng, 10.0, 10.0, 300.0, 0.02), trial % 2 ? 8 : 4, 1), "");
    e.setMorphRange(trial % 3 == 0 ? 2.0 : 0.0);
    e.setMergeOnPath(trial % 3 == 0);
    const gmm::Heightfield& hf = e.heightfield();
    const gmm::Quadtree& qt = e.quadtree();
    const gmm::ErrorTable& table = e.terrain()->table;
    const double ext = std::max(nx, ny) * 10.0;
    for (int k = 0; k < 12; ++k)
    {
      gmm::View v;
      v.eye = { randReal(rng, -0.5, 1.5) * ext, randReal(rng, -0.5, 1.5) * ext, randReal(rng, 200.0, 3000.0) };
      v.forward = glm::normalize(glm::dvec3(0.5 * ext, 0.5 * ext, 150.0) - v.eye);
      v.up = { 0, 0, 1 };
      v.viewportWidth = 1280;
      v.viewportHeight = 720;
      v.fovYDegrees = 50;
      v.nearDistance = 1.0;
      v.farDistance = 10 * ext;
      const double tau = randReal(rng, 0.5, 8.0);
      e.update(v, tau);
      ++frames;
      // Watertight over the drawn blocks, and the independent screen measure within tau.
      expectGoodFrame(e, &v, tau, "trial " + std::to_string(trial) + " frame " + std::to_string(k));
      const std::vector<int8_t> depth = drawnNodeDepths(e);
      const gmm::PerimeterContext across{ e.levels(), depth };
      for (std::size_t m = 0; m < e.mergedNodeList().size(); ++m)
      {
        const int node = e.mergedNodeList()[m];
        const gmm::QuadtreeNode& n = qt.nodes[node];
        const int d = e.mergedNodeDepths()[m];
        if (d >= n.height)
          continue;
        ++coarseFans;
        std::vector<uint32_t> indices;
        gmm::EmitScratch scratch;
        gmm::emitMergedNode(hf, qt, node, indices, scratch, &across);
        std::vector<Triangle> drawn;
        for (std::size_t t = 0; t + 2 < indices.size(); t += 3)
        {
          Triangle tri;
          for (int c = 0; c < 3; ++c)
            tri[c] = { static_cast<int>(indices[t + c] % hf.nx), static_cast<int>(indices[t + c] / hf.nx) };
          drawn.push_back(tri);
        }
        widened += drawn.size() > fanAtDepth(qt, node, d).size();
        const int i0 = qt.colStart[n.colBegin], i1 = qt.colStart[n.colEnd];
        const int j0 = qt.rowStart[n.rowBegin], j1 = qt.rowStart[n.rowEnd];
        const double error = largestDifference(paint(hf, drawn, i0, j0, i1, j1), samplesOf(hf, i0, j0, i1, j1));
        EXPECT_LE(error, table.perimeterError[table.perimeterFirst[node] + d] * (1 + 1e-6) + 1e-6)
          << "trial " << trial << " frame " << k << " node " << node << " depth " << d;
        // A coarse neighbour across one of its sides (east or north: each pair counted once).
        for (int c : { n.colEnd })
          if (c < qt.blockCols && e.levels()[qt.blockIndex(c, n.rowBegin)] == gmm::kCoveredLevel)
            coarseBesideCoarse += 1;
      }
      if (HasFailure())
        return;
    }
  }
  std::printf("[ coarse perimeter ] %d frames, %d coarse fans (%d with points their neighbours added), "
              "%d beside another merged node\n",
    frames, coarseFans, widened, coarseBesideCoarse);
  EXPECT_GT(coarseFans, frames);
  EXPECT_GT(widened, coarseFans / 10);
  EXPECT_GT(coarseBesideCoarse, 0);
}
