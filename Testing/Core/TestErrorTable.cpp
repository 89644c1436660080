// The error table's fast paths against the general rasteriser they replace, and its
// independence from the thread count. (The table's values themselves are checked against
// an independent measure in TestErrorCertification, TestViewIndependent and TestHandChecked.)
#include "CoreTestUtil.h"
#include "ErrorTable.h"
#include "Levels.h"
#include "Tessellate.h"

#include <gtest/gtest.h>

using namespace gmmtest;

namespace
{

// Rasterises the inner grid exactly as emitted and compares the direct walk with it.
void expectInnerAreasMatch(const gmm::Heightfield& hf, int maxBlockQuads)
{
  const gmm::Quadtree qt = gmm::buildQuadtree(hf, maxBlockQuads);
  gmm::EmitScratch scratch;
  std::vector<gmm::GridTriangle> tris;
  std::vector<int> C, R;
  int compared = 0;
  for (int b = 0; b < qt.blockCount(); ++b)
  {
    const int w = qt.blockWidth(b), h = qt.blockHeight(b);
    for (int m = 1; m <= gmm::topLevel(w, h); ++m)
    {
      if (gmm::blockShape(w, h, m) != gmm::BlockShape::Ring)
        continue;
      gmm::BlockConfig cfg;
      cfg.level = m;
      cfg.edgeLevel = { m, m, m, m };
      tris.clear();
      gmm::emitBlockGrid(qt, b, cfg, gmm::BlockPart::Inner, tris, scratch);
      const int c = b % qt.blockCols, r = b / qt.blockCols;
      gmm::edgeSamples(qt.colStart[c], qt.colStart[c + 1], m, C);
      gmm::edgeSamples(qt.rowStart[r], qt.rowStart[r + 1], m, R);
      const float fast = gmm::innerAreaError(hf, C, R);
      const float reference = gmm::trianglesError(hf, tris, true);
      // Bit-identical: the same integers and the same operations per sample; a sample on a
      // cell border is evaluated by one cell instead of two, which interpolate alike.
      ASSERT_EQ(fast, reference) << "block " << b << " (" << w << "x" << h << ") level " << m
                                 << ", " << hf.nx << "x" << hf.ny;
      ++compared;
    }
  }
  EXPECT_GT(compared, 0);
}

} // namespace

TEST(ErrorTable, InnerAreaWalkEqualsRasterisedInnerGrid)
{
  Rng rng(20261130);
  for (int k = 0; k < 60; ++k)
  {
    const int nx = randInt(rng, 5, 160), ny = randInt(rng, 5, 160);
    gmm::Heightfield hf = roughTerrain(nx, ny, rng, randReal(rng, 0.5, 50.0), randReal(rng, 0.5, 50.0));
    if (k % 4 == 1)
      hf.dx = -hf.dx; // mirrored: the emitter keeps grid order, the error must not care
    if (k % 5 == 2)
      for (float& z : hf.z)
        z = std::round(z / 50.0f) * 50.0f; // plateaus and cliffs: exact zeros and large steps
    expectInnerAreasMatch(hf, 4 << randInt(rng, 0, 5));
  }
}

TEST(ErrorTable, InnerAreaSeesNodata)
{
  Rng rng(7);
  gmm::Heightfield hf = roughTerrain(40, 40, rng);
  hf.z[hf.index(17, 23)] = std::numeric_limits<float>::quiet_NaN(); // inside the inner grid
  std::vector<int> C, R;
  gmm::edgeSamples(0, 39, 2, C);
  gmm::edgeSamples(0, 39, 2, R);
  EXPECT_EQ(gmm::innerAreaError(hf, C, R), std::numeric_limits<float>::infinity());
  gmm::edgeSamples(0, 39, 1, C);
  gmm::edgeSamples(0, 39, 1, R);
  EXPECT_EQ(gmm::innerAreaError(hf, C, R), std::numeric_limits<float>::infinity());
  // A corner of a cell (sample 20, 24 is a vertex at level 2).
  hf.z[hf.index(17, 23)] = 1.0f;
  hf.z[hf.index(20, 24)] = std::numeric_limits<float>::quiet_NaN();
  gmm::edgeSamples(0, 39, 2, C);
  gmm::edgeSamples(0, 39, 2, R);
  EXPECT_EQ(gmm::innerAreaError(hf, C, R), std::numeric_limits<float>::infinity());
}

TEST(ErrorTable, SameTableWithAnyThreadCount)
{
  Rng rng(11);
  gmm::Heightfield hf = roughTerrain(301, 173, rng);
  hf.z[hf.index(100, 50)] = std::numeric_limits<float>::quiet_NaN();
  const gmm::Quadtree qt = gmm::buildQuadtree(hf, 16);
  const gmm::ErrorTable one = gmm::buildErrorTable(hf, qt, 1);
  for (int threads : { 2, 3, 7 })
  {
    const gmm::ErrorTable t = gmm::buildErrorTable(hf, qt, threads);
    EXPECT_EQ(t.levels, one.levels);
    EXPECT_TRUE(t.ownError == one.ownError) << threads << " threads";
    EXPECT_TRUE(t.ownErrorExact == one.ownErrorExact) << threads << " threads";
    EXPECT_TRUE(t.stripError == one.stripError) << threads << " threads";
  }
}
