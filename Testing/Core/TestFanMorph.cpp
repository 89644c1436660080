// The fan morph (FanMorph.h, decision record 006): a node's block corners glide onto its
// fan before it merges, so that the merge moves the surface only by the table's residual.
// The tables are checked against fans and children built and rasterised here from the
// quadtree's bands alone; the frames against that fan, the independent screen measure and
// the drawn surfaces of consecutive frames.
#include "CoreTestUtil.h"
#include "Engine.h"
#include "FanMorph.h"
#include "Morph.h"
#include "MorphTestUtil.h"
#include "SyntheticTerrain.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace
{
struct Corner
{
  int i, j;
};

// Node `node`'s fan as the product defines it: from the point where the quadtree splits the
// node (mergedCentre) to every block corner along its perimeter, counter-clockwise.
std::vector<std::array<Corner, 3>> fanOf(const gmm::Quadtree& qt, int node)
{
  const gmm::QuadtreeNode& n = qt.nodes[node];
  std::vector<Corner> ring;
  const int i0 = qt.colStart[n.colBegin], i1 = qt.colStart[n.colEnd];
  const int j0 = qt.rowStart[n.rowBegin], j1 = qt.rowStart[n.rowEnd];
  for (int c = n.colBegin; c < n.colEnd; ++c)
    ring.push_back({ qt.colStart[c], j0 });
  for (int r = n.rowBegin; r < n.rowEnd; ++r)
    ring.push_back({ i1, qt.rowStart[r] });
  for (int c = n.colEnd; c > n.colBegin; --c)
    ring.push_back({ qt.colStart[c], j1 });
  for (int r = n.rowEnd; r > n.rowBegin; --r)
    ring.push_back({ i0, qt.rowStart[r] });
  const gmm::GridPoint centre = gmm::mergedCentre(qt, node);
  std::vector<std::array<Corner, 3>> fan;
  for (std::size_t k = 0; k < ring.size(); ++k)
    fan.push_back({ Corner{ centre.i, centre.j }, ring[k], ring[(k + 1) % ring.size()] });
  return fan;
}

// Writes into `out` (the node's rectangle, row by row from (i0, j0)) the heights that
// triangle t interpolates from `heightAt` at every sample it covers.
template <typename HeightAt>
void paint(const std::array<Corner, 3>& t, HeightAt heightAt, int i0, int j0, int width, std::vector<double>& out)
{
  gmmtest::paintTriangle(t[0].i, t[0].j, t[1].i, t[1].j, t[2].i, t[2].j, heightAt(t[0]), heightAt(t[1]),
    heightAt(t[2]), [&](int i, int j, double h) { out[static_cast<std::size_t>(j - j0) * width + (i - i0)] = h; });
}

// The node's children at their coarsest: a child of at least 2 x 2 blocks as its fan, any
// other block as its one quad, split along the diagonal the quadtree gives it.
std::vector<std::array<Corner, 3>> childrenOf(const gmm::Quadtree& qt, int node)
{
  std::vector<std::array<Corner, 3>> tris;
  const gmm::QuadtreeNode& n = qt.nodes[node];
  for (int k = 0; k < n.childCount; ++k)
  {
    const gmm::QuadtreeNode& q = qt.nodes[n.firstChild + k];
    if (q.colEnd - q.colBegin >= 2 && q.rowEnd - q.rowBegin >= 2)
    {
      const std::vector<std::array<Corner, 3>> fan = fanOf(qt, n.firstChild + k);
      tris.insert(tris.end(), fan.begin(), fan.end());
      continue;
    }
    for (int r = q.rowBegin; r < q.rowEnd; ++r)
      for (int c = q.colBegin; c < q.colEnd; ++c)
      {
        const Corner a{ qt.colStart[c], qt.rowStart[r] }, b{ qt.colStart[c + 1], qt.rowStart[r] };
        const Corner d{ qt.colStart[c], qt.rowStart[r + 1] }, e{ qt.colStart[c + 1], qt.rowStart[r + 1] };
        if (gmm::oneQuadAntiDiagonal(qt, qt.blockIndex(c, r)))
        {
          tris.push_back({ a, b, d });
          tris.push_back({ b, e, d });
        }
        else
        {
          tris.push_back({ a, b, e });
          tris.push_back({ a, e, d });
        }
      }
  }
  return tris;
}

struct NodeSurfaces
{
  int i0, j0, i1, j1, width;
  std::vector<double> fan, children, moved; // per sample of the node's rectangle
  double at(const std::vector<double>& s, int i, int j) const
  {
    return s[static_cast<std::size_t>(j - j0) * width + (i - i0)];
  }
};

NodeSurfaces surfacesOf(const gmm::Heightfield& hf, const gmm::Quadtree& qt, int node)
{
  const gmm::QuadtreeNode& n = qt.nodes[node];
  NodeSurfaces s;
  s.i0 = qt.colStart[n.colBegin];
  s.i1 = qt.colStart[n.colEnd];
  s.j0 = qt.rowStart[n.rowBegin];
  s.j1 = qt.rowStart[n.rowEnd];
  s.width = s.i1 - s.i0 + 1;
  const std::size_t count = static_cast<std::size_t>(s.width) * (s.j1 - s.j0 + 1);
  s.fan.assign(count, std::nan(""));
  s.children = s.moved = s.fan;
  auto own = [&](Corner p) { return double(hf.height(p.i, p.j)); };
  for (const auto& t : fanOf(qt, node))
    paint(t, own, s.i0, s.j0, s.width, s.fan);
  // Children's corners strictly inside the node on the fan, as the frame stores them (float).
  auto moved = [&](Corner p) {
    const bool perimeter = p.i == s.i0 || p.i == s.i1 || p.j == s.j0 || p.j == s.j1;
    return perimeter ? own(p) : double(static_cast<float>(s.at(s.fan, p.i, p.j)));
  };
  for (const auto& t : childrenOf(qt, node))
  {
    paint(t, own, s.i0, s.j0, s.width, s.children);
    paint(t, moved, s.i0, s.j0, s.width, s.moved);
  }
  return s;
}

// The largest distance (pixels) by which a sample of `node` in view moves on screen from
// heights `before` to heights `now` (NaN: not drawn), both seen by `cam`.
double worstPop(const gmm::Heightfield& hf, const gmm::Quadtree& qt, int node, const gmmtest::MyCamera& cam,
  const std::vector<double>& before, const std::vector<double>& now)
{
  const gmm::QuadtreeNode& n = qt.nodes[node];
  double worst = 0.0;
  for (int j = qt.rowStart[n.rowBegin]; j <= qt.rowStart[n.rowEnd]; ++j)
    for (int i = qt.colStart[n.colBegin]; i <= qt.colStart[n.colEnd]; ++i)
    {
      const std::size_t k = hf.index(i, j);
      const double x = hf.worldX(i), y = hf.worldY(j);
      double px, py, qx, qy;
      if (std::isnan(now[k]) || std::isnan(before[k]) || !gmmtest::insideFrustum(cam, x, y, hf.z[k]) ||
        gmmtest::project(cam, x, y, now[k], px, py) < cam.nearD ||
        gmmtest::project(cam, x, y, before[k], qx, qy) < cam.nearD)
        continue;
      worst = std::max(worst, std::hypot(px - qx, py - qy));
    }
  return worst;
}

// A table entry is its exact value rounded up to float.
void expectTableValue(float table, double exact, const char* what, int node)
{
  EXPECT_GE(table, exact - 1e-9 * std::max(1.0, exact)) << what << ", node " << node;
  EXPECT_LE(table, exact + 1e-3) << what << ", node " << node;
}
} // namespace

TEST(FanMorph, TablesMatchFansAndChildrenBuiltIndependently)
{
  // A size whose bands are not all equal, so that nodes split unevenly (splitBand).
  const gmm::Heightfield hf = gmm::makeSyntheticTerrain(301, 233, 30.0, 5, 1200.0, 1);
  const gmm::Quadtree qt = gmm::buildQuadtree(hf, 8);
  const gmm::ErrorTable t = gmm::buildErrorTable(hf, qt, 1);
  int checked = 0, moving = 0;
  double worstFanGap = 0.0;
  for (int node = 0; node < static_cast<int>(qt.nodes.size()); ++node)
  {
    const gmm::QuadtreeNode& n = qt.nodes[node];
    const bool fourQuads = n.colEnd - n.colBegin == 2 && n.rowEnd - n.rowBegin == 2;
    if (!gmm::fanMorphs(t, node))
    {
      // Only nodes that are not mergeable, and 2 x 2 nodes (whose fans nest), are left out
      // on terrain without nodata whose nodes are all exact.
      EXPECT_TRUE(n.colEnd - n.colBegin < 2 || n.rowEnd - n.rowBegin < 2 || fourQuads) << "node " << node;
      continue;
    }
    const NodeSurfaces s = surfacesOf(hf, qt, node);
    double residual = 0.0, moved = 0.0, children = 0.0;
    for (int j = s.j0; j <= s.j1; ++j)
      for (int i = s.i0; i <= s.i1; ++i)
      {
        const double h = hf.height(i, j), fan = s.at(s.fan, i, j);
        ASSERT_FALSE(std::isnan(fan) || std::isnan(s.at(s.moved, i, j))) << "uncovered sample, node " << node;
        residual = std::max(residual, std::abs(s.at(s.moved, i, j) - fan));
        moved = std::max(moved, std::abs(s.at(s.moved, i, j) - h));
        children = std::max(children, std::abs(s.at(s.children, i, j) - h));
        worstFanGap = std::max(worstFanGap, std::abs(gmm::fanSurfaceHeight(hf, qt, node, i, j) - fan));
      }
    expectTableValue(t.fanResidual[node], residual, "residual", node);
    expectTableValue(t.fanMovedError[node], moved, "moved children's error", node);
    expectTableValue(t.fanChildrenError[node], children, "children's error", node);
    ++checked;
    moving += residual < children ? 1 : 0;
  }
  EXPECT_LT(worstFanGap, 1e-6);
  std::printf("[ fan morph ] %d nodes' tables checked, %d with a residual below their children's error; "
              "fanSurfaceHeight within %.2e of the fan\n",
    checked, moving, worstFanGap);
  EXPECT_GE(checked, 50);
  EXPECT_GE(moving, checked / 2);
}

// A high flight over a fractal of 300 m relief at tau 2 with the mapper's defaults (block
// 16, so that the view holds many mergeable nodes, far enough to merge): every interior
// corner of a node whose children glide is drawn at h + t (fan - h) with the fan built here;
// the morphed surface is within tau by the independent measure; and where a node merges or
// splits between two frames, its samples move on screen (same camera, the heights of the
// two frames) by no more than the gate, kMergePopPixels. With the corners held still the
// worst is 1.59 px.
TEST(FanMorph, CornersGlideOntoTheFanAndMergesDoNotPop)
{
  const gmm::Heightfield input = gmm::makeSyntheticTerrain(1025, 1025, 30.0, 1, 300.0, 1);
  const int block = 16;
  const double tau = 2.0;
  gmm::Engine e;
  ASSERT_EQ(e.setHeightfield(input, block, 1), "");
  e.setMorphRange(gmm::kDefaultMorphRange);
  e.setMergeOnPath(true);
  const gmm::Heightfield& hf = e.heightfield();
  const gmm::Quadtree& qt = e.quadtree();
  const double top = gmmtest::highestSample(hf);
  gmm::MorphCache cache;
  std::vector<double> previous;
  std::vector<uint8_t> wasMerged(qt.nodes.size(), 0), wasGliding(qt.nodes.size(), 0);
  std::size_t gliding = 0, corners = 0, transitions = 0, fromGliding = 0;
  double worstTransitionPop = 0.0, worstCornerGap = 0.0;
  for (int f = 0; f < 40; ++f)
  {
    gmm::View v = gmmtest::poppingFlightView(hf, top, block, 0.3, f);
    v.eye.z += 1500.0; // high: far terrain in nodes
    e.update(v, tau);
    ASSERT_EQ(e.lastError(), "");
    gmm::MorphFrame mf;
    gmm::computeMorph(hf, qt, e.levels(), e.pixelFactors(), tau, cache, mf, e.morphRamp());
    std::vector<uint8_t> merged(qt.nodes.size(), 0), glides(qt.nodes.size(), 0);
    for (int n : e.mergedNodeList())
      merged[n] = 1;
    for (const gmm::FanPremerge& p : e.morphRamp()->premerging)
    {
      glides[p.node] = 1;
      ++gliding;
      const NodeSurfaces s = surfacesOf(hf, qt, p.node);
      const gmm::QuadtreeNode& n = qt.nodes[p.node];
      for (int r = n.rowBegin + 1; r < n.rowEnd; ++r)
        for (int c = n.colBegin + 1; c < n.colEnd; ++c)
        {
          const int i = qt.colStart[c], j = qt.rowStart[r];
          const double h = hf.height(i, j), fan = static_cast<float>(s.at(s.fan, i, j));
          const double drawn = gmm::morphedHeight(hf, qt, e.levels(), mf, i, j);
          worstCornerGap = std::max(worstCornerGap, std::abs(drawn - (h + p.t * (fan - h))));
          ++corners;
        }
    }
    const std::vector<double> z = gmmtest::morphedHeights(e, mf);
    const gmmtest::ScreenMeasure m = gmmtest::measureScreenError(hf, e.indices(), &v, tau,
      gmmtest::MeasureTransform(), z.data());
    EXPECT_EQ(m.violations, 0u) << "frame " << f << ": " << m.first;
    const gmmtest::SurfaceSample surface = gmmtest::sampleSurface(hf, e.indices(), z.data());
    if (!previous.empty())
    {
      const gmmtest::MyCamera cam = gmmtest::makeCamera(v);
      for (int node = 0; node < static_cast<int>(qt.nodes.size()); ++node)
      {
        // A fan-morph node that merged or split.
        if (!gmm::fanMorphs(e.errorTable(), node) || merged[node] == wasMerged[node])
          continue;
        fromGliding += (merged[node] ? wasGliding[node] : glides[node]) ? 1 : 0;
        ++transitions;
        worstTransitionPop = std::max(worstTransitionPop, worstPop(hf, qt, node, cam, previous, surface.z));
      }
    }
    previous = surface.z;
    wasMerged = merged;
    wasGliding = glides;
  }
  std::printf("[ fan morph ] 40 frames: %zu gliding nodes (%zu corners within %.2e of h + t (fan - h)), "
              "%zu merges or splits (%zu from or to gliding), worst pop at them %.3f px\n",
    gliding, corners, worstCornerGap, transitions, fromGliding, worstTransitionPop);
  EXPECT_GE(gliding, 20u);
  EXPECT_GE(transitions, 5u);
  EXPECT_LT(worstCornerGap, 1e-3);
  EXPECT_LE(worstTransitionPop, gmm::kMergePopPixels + 0.05);
}
