// blockTriangleCount against what emitBlock actually emits, for every block shape, level
// and many edge-level combinations (the budget is spent on these counts).
#include "CoreTestUtil.h"
#include "Levels.h"
#include "Tessellate.h"
#include "ErrorTable.h"
#include "TriangleCount.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

using namespace gmmtest;

namespace
{
gmm::Heightfield flatField(int nx, int ny)
{
  gmm::Heightfield hf;
  hf.nx = nx;
  hf.ny = ny;
  hf.z.assign(static_cast<std::size_t>(nx) * ny, 1.0f);
  return hf;
}
} // namespace

TEST(TriangleCount, MatchesEmitBlockForEveryLevelAndEdges)
{
  Rng rng(14);
  // Sizes giving ring, one-quad and thin blocks, odd remainders and unequal bands.
  const int sizes[][3] = { { 65, 65, 16 }, { 70, 41, 16 }, { 2, 40, 8 }, { 33, 2, 8 }, { 100, 77, 32 },
    { 6, 9, 4 } };
  int checked = 0;
  for (const auto& sz : sizes)
  {
    const gmm::Heightfield hf = flatField(sz[0], sz[1]);
    const gmm::Quadtree qt = gmm::buildQuadtree(hf, sz[2]);
    for (int b = 0; b < qt.blockCount(); ++b)
    {
      const int w = qt.blockWidth(b), h = qt.blockHeight(b);
      const int top = refTopLevel(w, h);
      for (int m = 0; m <= top; ++m)
      {
        if (!refLevelValid(w, h, m))
          continue;
        for (int trial = 0; trial < 12; ++trial)
        {
          gmm::BlockConfig cfg;
          cfg.level = m;
          for (int s = 0; s < 4; ++s)
            cfg.edgeLevel[s] = trial == 0 ? m : randInt(rng, m, top + 1);
          std::vector<uint32_t> out;
          gmm::emitBlock(hf, qt, b, cfg, gmm::BlockPart::Whole, out, true);
          ASSERT_EQ(gmm::blockTriangleCount(qt, b, cfg), out.size() / 3)
            << sz[0] << "x" << sz[1] << " block " << b << " (" << w << "x" << h << ") level " << m
            << " edges " << cfg.edgeLevel[0] << "," << cfg.edgeLevel[1] << "," << cfg.edgeLevel[2]
            << "," << cfg.edgeLevel[3];
          ++checked;
        }
      }
    }
  }
  EXPECT_GT(checked, 1000);
}

// With nodata emitBlock drops the triangles with a nodata corner: the count is what it draws,
// by hand for one sample at full resolution. Full resolution splits cell (u, v) on its
// (u, v)-(u+1, v+1) diagonal where u + v is even, on the other one where it is odd (the
// union-jack rule), so the four cells around a sample whose i + j is even all have a diagonal
// ending there (8 triangles touch it), and around one whose i + j is odd none has (4).
TEST(TriangleCount, CountsWhatBlocksWithNodataDraw)
{
  for (const auto& sample : { std::pair<int, std::size_t>{ 10, 8 }, std::pair<int, std::size_t>{ 11, 4 } })
  {
    gmm::Heightfield hf = flatField(65, 65);
    hf.z[hf.index(10, sample.first)] = std::numeric_limits<float>::quiet_NaN();
    const gmm::Quadtree qt = gmm::buildQuadtree(hf, 32);
    gmm::BlockConfig cfg;
    cfg.level = 0;
    cfg.edgeLevel = { 0, 0, 0, 0 };
    std::vector<uint32_t> out;
    gmm::emitBlock(hf, qt, 0, cfg, gmm::BlockPart::Whole, out);
    EXPECT_EQ(out.size() / 3, 2u * 32 * 32 - sample.second) << "nodata at (10, " << sample.first << ")";
    EXPECT_EQ(gmm::blockTriangleCount(qt, 0, cfg), 2u * 32 * 32 - sample.second);
  }
}

// Blocks with voids at coarse levels are drawn as cells (HoleCells.h) and side strips where
// their border rows are clear, and sides beside them at full resolution where they are
// not, in their neighbours too (a one-quad neighbour as a fan): the count is exactly what
// emitBlock draws, at any edge levels a side can take, both when counted here and when read
// from the error table's per-level counts.
TEST(TriangleCount, MatchesEmitBlockAroundVoids)
{
  Rng rng(15);
  int checked = 0, fromTable = 0, strips = 0;
  for (int trial = 0; trial < 12; ++trial)
  {
    const int maxQ = 16 << randInt(rng, 0, 1);
    gmm::Heightfield hf = flatField(randInt(rng, 40, 120), randInt(rng, 40, 120));
    for (int k = randInt(rng, 1, 12); k > 0; --k)
    {
      // a small void: a few samples around a random one
      const int ci = randInt(rng, 0, hf.nx - 1), cj = randInt(rng, 0, hf.ny - 1);
      for (int n = randInt(rng, 1, 6); n > 0; --n)
        hf.z[hf.index(std::clamp(ci + randInt(rng, -2, 2), 0, hf.nx - 1),
          std::clamp(cj + randInt(rng, -2, 2), 0, hf.ny - 1))] = std::numeric_limits<float>::quiet_NaN();
    }
    const gmm::Quadtree qt = gmm::buildQuadtree(hf, maxQ);
    const gmm::ErrorTable table = gmm::buildErrorTable(hf, qt, 1);
    for (int b = 0; b < qt.blockCount(); ++b)
    {
      bool besideNodata = false;
      for (int s = 0; s < 4; ++s)
        besideNodata = besideNodata || qt.sideAtFullResolution(b, s);
      if (!besideNodata)
        continue;
      const int w = qt.blockWidth(b), h = qt.blockHeight(b);
      const int top = refTopLevel(w, h);
      for (int m = 0; m <= top; ++m)
      {
        if (!refLevelValid(w, h, m) || std::isinf(table.own(b, m)))
          continue; // never drawn (a one-quad level over nodata, or a dominated one)
        gmm::BlockConfig cfg;
        cfg.level = m;
        for (int s = 0; s < 4; ++s)
        {
          // Full resolution where the side cannot follow the edge levels, else the level
          // or coarser, or full resolution beside a block that does not follow them.
          const bool fine = qt.sideAtFullResolution(b, s);
          const bool follows = qt.followsEdgeLevels(b, s, m);
          cfg.edgeLevel[s] = (fine && (!follows || randInt(rng, 0, 1) == 0)) ? 0 : randInt(rng, m, top + 1);
          strips += qt.blockHasNodata[b] && follows ? 1 : 0;
        }
        std::vector<uint32_t> drawn;
        gmm::emitBlock(hf, qt, b, cfg, gmm::BlockPart::Whole, drawn);
        const std::size_t count = gmm::blockTriangleCount(qt, b, cfg);
        ASSERT_EQ(count, drawn.size() / 3) << "block " << b << " (" << w << "x" << h << ") level " << m;
        ASSERT_EQ(gmm::blockTriangleCount(qt, b, cfg, &table), count) << "block " << b << " level " << m;
        ++checked;
        fromTable += qt.blockHasNodata[b] && gmm::blockShape(w, h, m) == gmm::BlockShape::Ring ? 1 : 0;
      }
    }
  }
  EXPECT_GT(checked, 100);
  EXPECT_GT(fromTable, 50);
  EXPECT_GT(strips, 50);
}
