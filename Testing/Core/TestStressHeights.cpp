// Heights (issue #6): flat, Earth's full range, spikes, steps, nodata of every extent, +-Inf
// and float extremes. Each DEM either renders (checked by expectGoodFrame: watertight,
// certified, no index on nodata, finite error table) or is refused with a clear error.
#include "StressUtil.h"

#include <gtest/gtest.h>

#include <cfloat>

using namespace gmmtest;

namespace
{
const float kNaN = std::numeric_limits<float>::quiet_NaN();
const float kInfF = std::numeric_limits<float>::infinity();

// Renders `hf` view-independently and from two cameras; checks every frame.
void expectRenders(const gmm::Heightfield& hf, const std::string& what, int maxQ = 16)
{
  gmm::Engine e;
  ASSERT_EQ(e.setHeightfield(hf, maxQ, 1), "") << what;
  for (double err : { 0.0, 1.0, 1e9 })
  {
    const gmm::FrameStats s = e.updateForError(err);
    expectGoodFrame(e, nullptr, 0.0, what + ", maxError " + std::to_string(err));
    EXPECT_LE(s.maxGeometricError, err) << what;
  }
  double zmax = -1e300;
  for (float z : e.heightfield().z)
    if (std::isfinite(z))
      zmax = std::max(zmax, double(z));
  if (zmax < -1e299)
    zmax = 0.0;
  gmm::View a = overview(hf, std::min(zmax, 1e6) + 1500.0); // oblique
  gmm::View b = a;
  b.parallel = true;
  b.parallelScale = 3000.0;
  for (const gmm::View& v : { a, b })
    for (double tau : { 0.5, 3.0 })
    {
      e.update(v, tau);
      const std::string mode = v.parallel ? ", parallel" : ", perspective";
      expectGoodFrame(e, &v, tau, what + mode + " tau " + std::to_string(tau));
    }
}

gmm::Heightfield flatDem(int nx, int ny, float h)
{
  gmm::Heightfield hf = hillsDem(nx, ny);
  std::fill(hf.z.begin(), hf.z.end(), h);
  return hf;
}
} // namespace

// A flat or exactly planar DEM has zero error at every level: maxError 0 already gives the
// coarsest frame: the root drawn whole with merged nodes, else one quad a block.
TEST(StressHeights, FlatAndPlanarAreCoarsestAtZeroError)
{
  gmm::Heightfield plane = flatDem(97, 89, 0.0f);
  for (int j = 0; j < plane.ny; ++j)
    for (int i = 0; i < plane.nx; ++i)
      plane.z[plane.index(i, j)] = static_cast<float>(100.0 + 0.25 * i - 0.75 * j);
  for (const auto& [hf, name] : { std::pair{ flatDem(97, 89, 123.5f), "flat" }, std::pair{ plane, "plane" } })
  for (bool merged : { true, false })
  {
    gmm::Engine e;
    ASSERT_EQ(e.setHeightfield(hf, 16, 1), "");
    e.setMergedNodes(merged);
    const gmm::FrameStats s = e.updateForError(0.0);
    const gmm::Quadtree& qt = e.quadtree();
    for (int b = 0; b < qt.blockCount(); ++b)
      EXPECT_EQ(e.levels()[b], merged ? gmm::kCoveredLevel : refTopLevel(qt.blockWidth(b), qt.blockHeight(b)))
        << name << " block " << b;
    EXPECT_EQ(s.triangles, coarsestTriangles(qt, merged)) << name;
    EXPECT_EQ(s.maxGeometricError, 0.0) << name;
    expectGoodFrame(e, nullptr, 0.0, name);
    expectRenders(hf, name);
  }
}

TEST(StressHeights, EarthRangeSpikesAndSteps)
{
  gmm::Heightfield earth = hillsDem(129, 111, 30.0, 30.0, 1.0, 0.0); // heights in [0, ~1]
  for (float& z : earth.z)
    z = -11000.0f + 19848.0f * z; // Challenger Deep .. Everest
  earth.z[0] = -11000.0f;
  earth.z[5] = 8848.0f;
  expectRenders(earth, "-11000..8848 m");

  for (float spike : { 5000.0f, -5000.0f })
  {
    gmm::Heightfield hf = flatDem(129, 111, 100.0f);
    hf.z[hf.index(64, 55)] += spike; // a single sample, mid-block
    hf.z[hf.index(0, 0)] += spike;   // a DEM corner
    hf.z[hf.index(16, 27)] += spike; // on a block corner (block size 16: rows 0, 13, 27, ...)
    expectRenders(hf, "single spikes " + std::to_string(spike));
  }
  gmm::Heightfield steps = hillsDem(129, 111);
  for (int j = 0; j < steps.ny; ++j)
    for (int i = 0; i < steps.nx; ++i)
      steps.z[steps.index(i, j)] += (i > 40 ? 1000.0f : 0.0f) - (j > 70 ? 2500.0f : 0.0f) + (i > 100 ? 300.0f : 0.0f);
  expectRenders(steps, "cliffs");
}

// Nodata: scattered holes, a whole block, everything but one block, and every sample.
// Decision (Engine.h): an all-nodata DEM is accepted and draws nothing, without error.
TEST(StressHeights, NodataHolesBlocksAndAll)
{
  gmm::Heightfield holes = hillsDem(129, 111);
  for (int k = 0; k < 40; ++k)
    holes.z[(k * 7919) % holes.z.size()] = kNaN;
  expectRenders(holes, "scattered holes");

  gmm::Heightfield block = hillsDem(129, 111);
  const gmm::Quadtree qt = gmm::buildQuadtree(block, 16);
  const int i0 = qt.colStart[1], i1 = qt.colStart[2], j0 = qt.rowStart[1], j1 = qt.rowStart[2];
  for (int j = j0; j <= j1; ++j) // exactly block (1, 1), borders included
    for (int i = i0; i <= i1; ++i)
      block.z[block.index(i, j)] = kNaN;
  expectRenders(block, "one whole block of nodata");
  {
    gmm::Engine e;
    ASSERT_EQ(e.setHeightfield(block, 16, 1), "");
    for (double err : { 0.0, 1e9 })
    {
      e.updateForError(err);
      for (uint32_t k : e.indices())
      {
        const int i = static_cast<int>(k % block.nx), j = static_cast<int>(k / block.nx);
        ASSERT_FALSE(i >= i0 && i <= i1 && j >= j0 && j <= j1) << "vertex on the void block";
      }
    }
  }

  gmm::Heightfield island = flatDem(65, 65, kNaN);
  for (int j = 32; j <= 48; ++j)
    for (int i = 32; i <= 48; ++i)
      island.z[island.index(i, j)] = static_cast<float>(10.0 * std::sin(0.3 * i) + j);
  expectRenders(island, "one valid block in a sea of nodata");

  for (auto [nx, ny] : { std::pair{ 2, 2 }, std::pair{ 97, 89 } })
  {
    gmm::Engine e;
    ASSERT_EQ(e.setHeightfield(flatDem(nx, ny, kNaN), 16, 1), "");
    EXPECT_EQ(e.updateForError(0.0).triangles, 0u);
    EXPECT_EQ(e.lastError(), "");
    const gmm::View v = overview(e.heightfield());
    const gmm::FrameStats& s = e.update(v, 1.0);
    EXPECT_EQ(e.lastError(), "");
    EXPECT_EQ(s.triangles, 0u);
    EXPECT_TRUE(e.indices().empty());
    EXPECT_EQ(s.maxGeometricError, 0.0);
    expectSaneErrorTable(e, "all nodata");
  }
}

// +-Inf samples are nodata (Heightfield.h): the engine's copy holds NaN there and no
// triangle uses them; the caller's heightfield is not modified.
TEST(StressHeights, InfinitiesAreNodata)
{
  gmm::Heightfield hf = hillsDem(129, 111);
  const std::size_t pos = hf.index(50, 50), neg = hf.index(17, 90);
  hf.z[pos] = kInfF;
  hf.z[neg] = -kInfF;
  gmm::Engine e;
  ASSERT_EQ(e.setHeightfield(hf, 16, 1), "");
  EXPECT_TRUE(std::isnan(e.heightfield().z[pos]));
  EXPECT_TRUE(std::isnan(e.heightfield().z[neg]));
  EXPECT_EQ(hf.z[pos], kInfF); // setHeightfield takes a copy
  expectRenders(hf, "+-Inf samples");
  gmm::Heightfield all = flatDem(9, 9, -kInfF);
  ASSERT_EQ(e.setHeightfield(all, 4, 1), "");
  EXPECT_EQ(e.updateForError(1.0).triangles, 0u);
}

// Float extremes: heights up to +-kMaxHeight (1e38) render with a finite error table;
// beyond it (FLT_MAX, the usual undeclared nodata -FLT_MAX) the DEM is refused, naming the
// sample and suggesting nodata. Tiny and denormal heights render.
TEST(StressHeights, FloatExtremes)
{
  for (float big : { 1e30f, -1e30f, 1e38f, -1e38f })
  {
    gmm::Heightfield hf = hillsDem(65, 65);
    hf.z[hf.index(20, 30)] = big;
    expectRenders(hf, "spike " + std::to_string(big));
  }
  gmm::Heightfield both = hillsDem(65, 65);
  both.z[both.index(20, 30)] = 1e38f; // adjacent extremes: errors up to 2e38, still finite
  both.z[both.index(21, 30)] = -1e38f;
  expectRenders(both, "+1e38 next to -1e38");
  gmm::Heightfield tiny = hillsDem(65, 65, 30.0, 30.0, 1e-30, 0.0);
  tiny.z[3] = FLT_TRUE_MIN;
  expectRenders(tiny, "heights ~1e-30 and a denormal");
  for (float bad : { FLT_MAX, -FLT_MAX, 2e38f })
  {
    gmm::Heightfield hf = hillsDem(65, 65);
    hf.z[hf.index(7, 3)] = bad;
    gmm::Engine e;
    const std::string err = e.setHeightfield(hf, 16, 1);
    EXPECT_NE(err.find("at sample (7, 3)"), std::string::npos) << err;
    EXPECT_NE(err.find("nodata"), std::string::npos) << err;
    EXPECT_TRUE(e.empty());
    EXPECT_EQ(gmm::validateHeightfield(hf), err);
  }
}
