// View-independent mode (Engine::updateForError): every sample's vertical distance to the
// drawn surface is within maxError, measured by our own rasteriser (CoreTestUtil.h).
// Float tolerance: heights are floats and the table stores floats: |dz| <= maxError *
// (1 + 1e-6) + 1e-5 m.
#include "CoreTestUtil.h"
#include "Engine.h"
#include "SyntheticTerrain.h"

#include <gtest/gtest.h>

using namespace gmmtest;

TEST(ViewIndependent, VerticalErrorBoundAndMonotoneTriangleCount)
{
  Rng rng(31);
  for (int t = 0; t < 12; ++t)
  {
    const int nx = randInt(rng, 30, 220), ny = randInt(rng, 30, 220), maxQ = 1 << randInt(rng, 2, 6);
    gmm::Heightfield hf = (t % 2) ? roughTerrain(nx, ny, rng, 5.0, randInt(rng, 0, 1) ? 5.0 : -5.0, 500.0, 0.01)
                                  : gmm::makeSyntheticTerrain(nx, ny, 20.0, 100 + t, 1200.0, 1);
    gmm::Engine e;
    ASSERT_EQ(e.setHeightfield(hf, maxQ, 1), "");
    std::size_t prevTris = std::numeric_limits<std::size_t>::max();
    for (double maxErr : { 0.0, 0.01, 0.1, 0.5, 1.0, 3.0, 10.0, 30.0, 100.0, 1e4 })
    {
      const gmm::FrameStats st = e.updateForError(maxErr);
      ASSERT_EQ(st.triangles * 3, e.indices().size());
      const SurfaceSample s = sampleSurface(hf, e.indices(), drawnHeights(e).data());
      double worst = 0.0;
      std::size_t uncovered = 0;
      for (std::size_t k = 0; k < hf.z.size(); ++k)
      {
        if (std::isnan(s.z[k]))
        {
          ++uncovered;
          continue;
        }
        worst = std::max(worst, std::fabs(s.z[k] - hf.z[k]));
      }
      EXPECT_EQ(uncovered, 0u) << nx << "x" << ny << " maxErr " << maxErr;
      EXPECT_LE(worst, maxErr * (1 + 1e-6) + 1e-5) << nx << "x" << ny << " block " << maxQ << " maxErr " << maxErr;
      EXPECT_LE(st.maxGeometricError, maxErr * (1 + 1e-6) + 1e-6);
      EXPECT_LE(worst, st.maxGeometricError * (1 + 1e-6) + 1e-5) << "engine's reported bound is exceeded";
      EXPECT_LE(st.triangles, prevTris) << "maxErr " << maxErr << " gave more triangles than a smaller one";
      prevTris = st.triangles;
      if (maxErr == 0.0)
        EXPECT_EQ(st.triangles, 2 * static_cast<std::size_t>(nx - 1) * (ny - 1));
      if (maxErr == 1e4)
        EXPECT_EQ(st.triangles, coarsestTriangles(e.quadtree()))
          << "a huge tolerance should draw the root whole, or every block as one quad";
      MeshCheckResult mc = checkMesh(hf, e.quadtree().colStart, e.quadtree().rowStart, e.indices(), {});
      EXPECT_EQ(mc.error, "") << nx << "x" << ny << " maxErr " << maxErr;
    }
  }
}

TEST(ViewIndependent, BadMaxErrorIsRefused)
{
  Rng rng(1);
  gmm::Engine e;
  ASSERT_EQ(e.setHeightfield(roughTerrain(20, 20, rng), 8, 1), "");
  for (double bad : { -1.0, std::numeric_limits<double>::quiet_NaN() })
  {
    const gmm::FrameStats& st = e.updateForError(bad);
    EXPECT_FALSE(e.lastError().empty()) << bad;
    EXPECT_EQ(st.triangles, 0u) << bad;
    EXPECT_TRUE(e.indices().empty()) << bad;
  }
}
