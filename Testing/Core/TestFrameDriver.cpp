// The frame recipe (Frame.h): what the mapper and the filter run every frame. Each frame it
// returns is measured against the full-resolution samples with the tests' own projection
// (measureScreenError), not against the bound the driver reports.
#include "CoreTestUtil.h"
#include "Frame.h"
#include "MorphTestUtil.h"
#include "Terrain.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

namespace
{
using gmmtest::Rng;

std::shared_ptr<const gmm::Terrain> roughTerrainOf(Rng& rng, int n, int block)
{
  std::shared_ptr<const gmm::Terrain> t;
  const std::string err = gmm::buildTerrain(gmmtest::roughTerrain(n, n, rng), block, 1, t);
  EXPECT_EQ(err, "");
  return t;
}

// The drawn surface of the driver's frame measured against every sample in view.
gmmtest::ScreenMeasure measureFrame(const gmm::FrameDriver& d, const gmm::View* view, double tau)
{
  const gmm::Engine& e = d.engine();
  gmmtest::MeasureTransform toWorld;
  toWorld.z0 = e.heightfield().z0;
  toWorld.heightScale = e.heightScale();
  // Morphed or not, the driver's frame places every vertex (glided edges' on their polylines).
  const std::vector<double> z = gmmtest::morphedHeights(e, d.morph());
  return gmmtest::measureScreenError(e.heightfield(), e.indices(), view, tau, toWorld, z.data());
}
} // namespace

// Every kind of frame the consumers ask for (geomorphing on or off, on the level path or
// morphing as far as the certificate allows, merges on the path, a budget, a height
// scale), along random views: the drawn surface, morphed when the frame says so, is within
// tau (or a budgeted frame's reported error) where measured.
TEST(FrameDriver, DrawnSurfaceWithinTheFramesBound)
{
  Rng rng(71);
  int drawnFrames = 0;
  for (int trial = 0; trial < 8; ++trial)
  {
    gmm::FrameDriver d;
    d.setTerrain(roughTerrainOf(rng, gmmtest::randInt(rng, 60, 140), gmmtest::randInt(rng, 8, 32)));
    gmm::FrameSettings s;
    s.pixelError = gmmtest::randReal(rng, 0.5, 4.0);
    s.geomorphing = trial % 3 != 2;
    s.geomorphMerges = trial % 2 == 1;
    s.geomorphRange = trial % 4 < 2 ? 1.0 : gmm::kDefaultMorphRange;
    s.heightScale = gmmtest::randReal(rng, 0.5, 2.0);
    s.triangleBudget = trial >= 6 ? static_cast<std::size_t>(gmmtest::randInt(rng, 500, 4000)) : 0;
    s.budgetWarmStart = true;
    int morphedFrames = 0;
    for (int f = 0; f < 8; ++f)
    {
      const gmm::View v = gmmtest::randomViewOver(d.engine().heightfield(), rng);
      const gmm::Frame& frame = d.update(v, s);
      ASSERT_TRUE(frame.ok()) << frame.error;
      EXPECT_EQ(frame.morphed, s.geomorphing && frame.stats.triangles > 0);
      morphedFrames += frame.morphed ? 1 : 0;
      drawnFrames += frame.stats.triangles > 0 ? 1 : 0;
      const double allowed = s.triangleBudget > 0 ? frame.stats.maxScreenError : s.pixelError;
      const gmmtest::ScreenMeasure m = measureFrame(d, &v, allowed);
      EXPECT_EQ(m.violations, 0u) << "trial " << trial << " frame " << f << ": " << m.first;
      EXPECT_EQ(m.uncovered, 0u) << m.first;
    }
    if (s.geomorphing)
      EXPECT_GT(morphedFrames, 0);
  }
  EXPECT_GE(drawnFrames, 32); // random views: at least half of them see terrain
}

// A renderer's budgeted frames start their search at the last budgeted frame's tau
// (budgetWarmStart); another driver given that start explicitly draws the same triangles,
// which is how the filter reproduces a frame the mapper drew. A new terrain starts cold.
TEST(FrameDriver, WarmStartReproducedFromTheReportedStart)
{
  Rng rng(5);
  std::shared_ptr<const gmm::Terrain> terrain = roughTerrainOf(rng, 129, 16);
  gmm::FrameDriver mapper, filter;
  mapper.setTerrain(terrain);
  filter.setTerrain(terrain);
  gmm::FrameSettings warm;
  warm.triangleBudget = 3000;
  warm.pixelError = 0.0;
  warm.budgetWarmStart = true;
  double previousTau = 0.0;
  for (int f = 0; f < 10; ++f)
  {
    const gmm::View v = gmmtest::randomViewOver(terrain->hf, rng);
    const gmm::Frame& drawn = mapper.update(v, warm);
    ASSERT_TRUE(drawn.ok()) << drawn.error;
    EXPECT_EQ(drawn.stats.budgetStartTau, previousTau) << "frame " << f;
    previousTau = mapper.warmStartTau();
    EXPECT_EQ(previousTau, drawn.stats.budgetTau);

    gmm::FrameSettings given = warm;
    given.budgetWarmStart = false;
    given.budgetStartTau = drawn.stats.budgetStartTau;
    filter.update(v, given);
    EXPECT_EQ(filter.engine().indices(), mapper.engine().indices()) << "frame " << f;
  }
  EXPECT_GT(previousTau, 0.0);
  mapper.setTerrain(terrain);
  EXPECT_EQ(mapper.warmStartTau(), 0.0);
  EXPECT_EQ(mapper.update(gmmtest::randomViewOver(terrain->hf, rng), warm).stats.budgetStartTau, 0.0);
}

// A frozen LOD (keep): the selection and its triangles stay as they are. Geomorphing asked
// for while frozen morphs the kept selection, within tau where measured from its camera.
TEST(FrameDriver, KeepHoldsTheSelectionAndMorphsItOnRequest)
{
  Rng rng(11);
  gmm::FrameDriver d;
  d.setTerrain(roughTerrainOf(rng, 161, 16));
  EXPECT_FALSE(d.hasSelection());
  gmm::FrameSettings s;
  s.pixelError = 1.5;
  s.geomorphing = false;
  gmm::View v = gmmtest::randomViewOver(d.engine().heightfield(), rng);
  for (int tries = 0; tries < 20 && d.update(v, s).stats.triangles == 0; ++tries)
    v = gmmtest::randomViewOver(d.engine().heightfield(), rng);
  ASSERT_GT(d.frame().stats.triangles, 0u);
  EXPECT_FALSE(d.frame().morphed);
  const std::vector<uint32_t> before = d.engine().indices();

  s.geomorphing = true;
  const gmm::Frame& kept = d.keep(s);
  ASSERT_TRUE(kept.ok());
  EXPECT_TRUE(kept.morphed);
  EXPECT_EQ(d.engine().indices(), before);
  const gmmtest::ScreenMeasure m = measureFrame(d, &v, s.pixelError);
  EXPECT_EQ(m.violations, 0u) << m.first;

  s.geomorphing = false;
  EXPECT_FALSE(d.keep(s).morphed);
  EXPECT_EQ(d.engine().indices(), before);
}

// The view-independent frame: never morphed, every drawn sample within the vertical error.
TEST(FrameDriver, ViewIndependentFrameWithinItsVerticalError)
{
  Rng rng(3);
  gmm::FrameDriver d;
  d.setTerrain(roughTerrainOf(rng, 97, 8));
  gmm::FrameSettings s;
  s.heightScale = 1.5;
  const double maxError = 20.0;
  const gmm::Frame& f = d.updateForError(maxError, s);
  ASSERT_TRUE(f.ok()) << f.error;
  EXPECT_FALSE(f.morphed);
  EXPECT_GT(f.stats.triangles, 0u);
  const gmmtest::ScreenMeasure m = measureFrame(d, nullptr, 0.0);
  EXPECT_LE(m.maxVertical, maxError * (1 + 1e-9));
}

// A frame that cannot be drawn says why and draws nothing; so does a driver without terrain.
TEST(FrameDriver, RefusedFramesSayWhy)
{
  gmm::FrameDriver d;
  gmm::View v;
  const gmm::Frame& none = d.update(v, gmm::FrameSettings());
  EXPECT_FALSE(none.ok());
  EXPECT_NE(none.error.find("no heightfield"), std::string::npos) << none.error;
  EXPECT_EQ(none.stats.triangles, 0u);

  Rng rng(2);
  d.setTerrain(roughTerrainOf(rng, 65, 16));
  gmm::FrameSettings bad;
  bad.pixelError = -1.0;
  const gmm::Frame& refused = d.update(gmmtest::randomViewOver(d.engine().heightfield(), rng), bad);
  EXPECT_FALSE(refused.ok());
  EXPECT_NE(refused.error.find("pixel error"), std::string::npos) << refused.error;
  EXPECT_EQ(refused.stats.triangles, 0u);
  EXPECT_FALSE(refused.morphed);
  EXPECT_FALSE(d.hasSelection());
}
