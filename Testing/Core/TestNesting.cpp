// Levels that nest (Documentation/decisions/002-levels-that-nest.md): a block at level m
// with its vertices moved onto the surface of its next level m' draws exactly level m'.
// Measured independently of the engine's tables and morph rule: both levels' triangles come
// from emitBlock, each level-m vertex is placed on level m''s triangles as the test
// evaluates them (sampleSurface), and the two surfaces are compared at every sample of the
// block. The engine's morph targets (blockVertexTarget) are then checked against those
// placements.
#include "CoreTestUtil.h"
#include "Levels.h"
#include "Morph.h"
#include "Quadtree.h"
#include "Tessellate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace
{
using gmmtest::Rng;

struct NestingGap
{
  double surface = 0.0; // largest |level m at factor 1 - level m'| over the block's samples
  double target = 0.0;  // largest |engine's target - level m' at a level-m vertex|
  std::size_t samples = 0;
};

// Block `block` of `qt` with its own edges at level m and at its next valid level.
NestingGap nestingGap(const gmm::Heightfield& hf, const gmm::Quadtree& qt, int block, int m)
{
  NestingGap gap;
  const int w = qt.blockWidth(block), h = qt.blockHeight(block);
  const int next = gmm::nextValidLevel(w, h, m);
  auto ownEdges = [](int level) {
    gmm::BlockConfig cfg;
    cfg.level = level;
    cfg.edgeLevel = { level, level, level, level };
    return cfg;
  };
  std::vector<uint32_t> fine, coarse;
  gmm::emitBlock(hf, qt, block, ownEdges(m), gmm::BlockPart::Whole, fine, true);
  gmm::emitBlock(hf, qt, block, ownEdges(next), gmm::BlockPart::Whole, coarse, true);
  const gmmtest::SurfaceSample target = gmmtest::sampleSurface(hf, coarse);
  // Level m's vertices at factor 1: on level m''s surface.
  std::vector<double> moved(hf.z.begin(), hf.z.end());
  for (uint32_t v : fine)
    moved[v] = target.z[v];
  const gmmtest::SurfaceSample morphed = gmmtest::sampleSurface(hf, fine, moved.data());
  const int c = block % qt.blockCols, r = block / qt.blockCols;
  for (int j = qt.rowStart[r]; j <= qt.rowStart[r + 1]; ++j)
    for (int i = qt.colStart[c]; i <= qt.colStart[c + 1]; ++i)
    {
      const std::size_t k = hf.index(i, j);
      gap.surface = std::max(gap.surface, std::fabs(morphed.z[k] - target.z[k]));
      ++gap.samples;
    }
  for (uint32_t v : fine)
  {
    const int i = static_cast<int>(v % hf.nx), j = static_cast<int>(v / hf.nx);
    const double engine = gmm::blockVertexTarget(hf, qt, block, next, { next, next, next, next }, { m, m, m, m }, i, j);
    gap.target = std::max(gap.target, std::fabs(engine - target.z[v]));
  }
  return gap;
}
} // namespace

// Every ring level of power-of-two blocks (8, 16 and 32 quads, square and oblong DEMs, rough
// heights) nests in the next one, with its own edges: the inner grid, the side strips and
// the ring's corner cells.
TEST(Nesting, PowerOfTwoBlocksNestWithTheirOwnEdges)
{
  Rng rng(2026);
  int checked = 0;
  for (const int block : { 8, 16, 32 })
  {
    const int nx = 2 * block + 1, ny = (block == 16 ? 4 : 2) * block + 1;
    const gmm::Heightfield hf = gmmtest::roughTerrain(nx, ny, rng, 10.0, 10.0, 300.0, 0.3);
    const gmm::Quadtree qt = gmm::buildQuadtree(hf, block);
    for (int b = 0; b < qt.blockCount(); ++b)
    {
      ASSERT_EQ(qt.blockWidth(b), block);
      ASSERT_EQ(qt.blockHeight(b), block);
      for (int m = 0; gmm::nextValidLevel(block, block, m) >= 0; ++m)
      {
        const NestingGap gap = nestingGap(hf, qt, b, m);
        EXPECT_LE(gap.surface, 1e-9) << "block " << b << " of " << block << " quads, level " << m;
        EXPECT_LE(gap.target, 1e-9) << "block " << b << " of " << block << " quads, level " << m;
        EXPECT_EQ(gap.samples, static_cast<std::size_t>((block + 1) * (block + 1)));
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 40);
}

// The measure is not blind: a block whose step does not divide it (a thin last interval)
// cannot nest (a coarse cell split on one axis only has no fine vertex on its diagonals),
// and the same comparison finds the gap.
TEST(Nesting, ThinLastIntervalsDoNotNest)
{
  Rng rng(7);
  const gmm::Heightfield hf = gmmtest::roughTerrain(20, 20, rng, 10.0, 10.0, 300.0, 0.3);
  const gmm::Quadtree qt = gmm::buildQuadtree(hf, 32);
  ASSERT_EQ(qt.blockCount(), 1);
  ASSERT_EQ(qt.blockWidth(0), 19);
  EXPECT_GT(nestingGap(hf, qt, 0, 1).surface, 1e-3);
}

namespace
{
// The drawn surface of `levels` under `frame` (every vertex where morphedHeight places it),
// sampled by the test's own rasteriser.
gmmtest::SurfaceSample drawnSurface(const gmm::Heightfield& hf, const gmm::Quadtree& qt,
  const std::vector<int8_t>& levels, const gmm::MorphFrame& frame)
{
  std::vector<uint32_t> idx;
  gmm::tessellate(hf, qt, levels, idx);
  std::vector<double> z(hf.z.begin(), hf.z.end());
  for (uint32_t v : idx)
    z[v] = gmm::morphedHeight(hf, qt, levels, frame, static_cast<int>(v % hf.nx), static_cast<int>(v / hf.nx));
  return gmmtest::sampleSurface(hf, idx, z.data());
}
} // namespace

// Levels that nest across edges too (the nesting test): 4 x 4 power-of-two blocks,
// block (1, 1) at level m with its interior fully morphed toward m + 1 (factor 1) against
// the same frame with the centre block at m + 1, over random levels of its neighbours
// and the other blocks (finer, the same, coarser by any number of levels, not drawn). An
// edge toward a coarser neighbour is glided (its samples at m on the neighbour's polyline)
// and moves toward that neighbour's next level by a random factor, the same in both
// frames; an edge the block sets at m goes with it (factor 1), and at m + 1 is where m's
// reached (factor 0).
// The two drawn surfaces (every triangle of the DEM, the connects included, rasterised by
// the test from the vertices' drawn heights) must be equal at every sample.
TEST(Nesting, GlidedEdgesNestAtAnyEdgeFactor)
{
  Rng rng(5150);
  int checked = 0, glided = 0, movingCoarser = 0;
  for (const int block : { 8, 16, 32 })
  {
    const int n = 4 * block + 1;
    const gmm::Heightfield hf = gmmtest::roughTerrain(n, n, rng, 10.0, 10.0, 300.0, 0.3);
    const gmm::Quadtree qt = gmm::buildQuadtree(hf, block);
    ASSERT_EQ(qt.blockCount(), 16);
    ASSERT_EQ(qt.blockWidth(0), block);
    const int centre = qt.blockIndex(1, 1), top = gmm::topLevel(block, block);
    for (int trial = 0; trial < 60; ++trial)
    {
      const int m = gmmtest::randInt(rng, 0, top - 1);
      std::vector<int8_t> fine(16), coarse;
      for (int b = 0; b < 16; ++b)
        fine[b] = static_cast<int8_t>(gmmtest::randInt(rng, -1, top));
      fine[centre] = static_cast<int8_t>(m);
      coarse = fine;
      coarse[centre] = static_cast<int8_t>(m + 1);
      gmm::MorphFrame a, c;
      gmm::drawnEdgeFrame(qt, fine, a);
      gmm::drawnEdgeFrame(qt, coarse, c);
      a.blockTarget[centre] = static_cast<int8_t>(m + 1);
      a.blockT[centre] = 1.0f;
      const std::array<int, 4> nb = qt.blockNeighbours(centre);
      const std::array<const gmm::MorphEdge*, 4> ea = gmm::blockEdges(qt, a, centre);
      const std::array<const gmm::MorphEdge*, 4> ec = gmm::blockEdges(qt, c, centre);
      for (int s = 0; s < 4; ++s)
      {
        auto* edgeA = const_cast<gmm::MorphEdge*>(ea[s]);
        auto* edgeC = const_cast<gmm::MorphEdge*>(ec[s]);
        const int k = nb[s] >= 0 ? fine[nb[s]] : -1;
        if (k > m)
        {
          // The coarser neighbour sets the edge: toward its next level, the same in both.
          const int next = gmm::nextValidLevel(block, block, k);
          const float t = static_cast<float>(gmmtest::randInt(rng, 0, 4)) / 4.0f;
          edgeA->target = edgeC->target = static_cast<int8_t>(next);
          edgeA->t = edgeC->t = next >= 0 ? t : 0.0f;
          ++glided;
          movingCoarser += next >= 0 && t > 0.0f;
        }
        else
        {
          // The centre block sets it: at m it goes with the interior (factor 1), at m + 1
          // it starts there (factor 0).
          edgeA->target = static_cast<int8_t>(m + 1);
          edgeA->t = 1.0f;
        }
      }
      const gmmtest::SurfaceSample sa = drawnSurface(hf, qt, fine, a), sc = drawnSurface(hf, qt, coarse, c);
      double gap = 0.0;
      for (std::size_t k = 0; k < hf.z.size(); ++k)
      {
        ASSERT_EQ(std::isnan(sa.z[k]), std::isnan(sc.z[k])) << "sample " << k;
        if (!std::isnan(sa.z[k]))
          gap = std::max(gap, std::fabs(sa.z[k] - sc.z[k]));
      }
      EXPECT_LE(gap, 1e-9) << "block " << block << " trial " << trial << " level " << m;
      ++checked;
    }
  }
  std::printf("[ nesting ] %d frame pairs equal at every sample, %d edges toward coarser blocks (%d moving)\n",
    checked, glided, movingCoarser);
  EXPECT_GT(movingCoarser, 50);
}
