// Sizes and spacing (issue #6): every accepted shape renders correctly at full resolution,
// at the coarsest levels and from a camera scaled to the DEM; every refused one gives a
// clear error without allocating (the size checks run before any height is touched).
#include "StressUtil.h"

#include <gtest/gtest.h>

#include <climits>

using namespace gmmtest;

namespace
{
// Camera over the DEM scaled to its extent, whatever the spacing (1e-6 .. 1e5, flipped).
gmm::View scaledView(const gmm::Heightfield& hf)
{
  const double ex = std::abs(hf.dx) * (hf.nx - 1), ey = std::abs(hf.dy) * (hf.ny - 1);
  const double ext = std::max(ex, ey);
  gmm::View v;
  v.eye = { hf.worldX(0.5 * (hf.nx - 1)), hf.worldY(-0.3 * (hf.ny - 1)), 0.6 * ext };
  if (ey < 0.01 * ext) // a DEM far wider than tall: back off across it instead
    v.eye.y = hf.worldY(0) - 0.3 * ext;
  const double towards = hf.worldY(0.5 * (hf.ny - 1)) - v.eye.y;
  v.forward = { 0.0, towards, -0.6 * ext };
  v.fovYDegrees = 50.0;
  v.nearDistance = 1e-3 * ext;
  v.farDistance = 1e3 * ext;
  return v;
}

void expectSizeRenders(const gmm::Heightfield& hf, int maxQ, const std::string& what)
{
  gmm::Engine e;
  ASSERT_EQ(e.setHeightfield(hf, maxQ, 1), "") << what;
  const gmm::Quadtree& qt = e.quadtree();
  const gmm::FrameStats full = e.updateForError(0.0);
  expectGoodFrame(e, nullptr, 0.0, what + ", full resolution");
  EXPECT_EQ(full.maxGeometricError, 0.0) << what;
  const gmm::FrameStats coarse = e.updateForError(1e30);
  expectGoodFrame(e, nullptr, 0.0, what + ", coarsest");
  EXPECT_EQ(coarse.triangles, coarsestTriangles(qt))
    << what << ": the root whole, or one quad a block, expected";
  const gmm::View v = scaledView(hf);
  for (double tau : { 0.5, 4.0 })
  {
    const gmm::FrameStats s = e.update(v, tau);
    expectGoodFrame(e, &v, tau, what + ", view tau " + std::to_string(tau));
    EXPECT_GT(s.triangles, 0u) << what;
  }
}

gmm::Heightfield sized(int nx, int ny, double dx = 30.0, double dy = 30.0)
{
  return hillsDem(nx, ny, dx, dy, 0.3 * std::max(std::abs(dx), std::abs(dy)) * std::max(nx, ny), 0.0);
}
} // namespace

TEST(StressSizes, SmallThinAndPrimeSizes)
{
  const int sizes[][3] = { { 2, 2, 16 }, { 2, 37, 16 }, { 37, 2, 16 }, { 3, 3, 4 }, { 97, 89, 16 },
    { 1021, 7, 32 }, { 7, 1021, 32 }, { 33, 33, 32 }, { 17, 9, 64 }, { 50, 30, 1000 },
    { 61, 45, INT_MAX } };
  for (auto& s : sizes)
  {
    const std::string what = std::to_string(s[0]) + "x" + std::to_string(s[1]) + " block " + std::to_string(s[2]);
    expectSizeRenders(sized(s[0], s[1]), s[2], what);
    gmm::Engine e;
    ASSERT_EQ(e.setHeightfield(sized(s[0], s[1]), s[2], 1), "");
    const bool oneBlock = s[0] - 1 <= s[2] && s[1] - 1 <= s[2];
    EXPECT_EQ(e.quadtree().blockCount() == 1, oneBlock) << what;
    // every block at level 0: exactly two triangles a quad
    const std::vector<int8_t> finest(e.quadtree().blockCount(), 0);
    EXPECT_EQ(e.updateWithLevels(finest).triangles, 2u * (s[0] - 1) * (s[1] - 1)) << what;
    expectGoodFrame(e, nullptr, 0.0, what + ", all level 0");
  }
}

TEST(StressSizes, SpacingAnisotropicTinyHugeAndFlipped)
{
  struct Case
  {
    double dx, dy;
    const char* name;
  };
  const Case cases[] = { { 1.0, 1000.0, "anisotropic 1:1000" }, { 1000.0, 1.0, "anisotropic 1000:1" },
    { 1e-6, 1e-6, "tiny 1e-6" }, { 1e5, 1e5, "huge 1e5" }, { -30.0, 30.0, "dx < 0" },
    { 30.0, -30.0, "dy < 0" }, { -30.0, -30.0, "both < 0" }, { -1e-6, 1e5, "flipped tiny x huge" } };
  for (const Case& c : cases)
  {
    gmm::Heightfield hf = sized(97, 89, c.dx, c.dy);
    hf.x0 = -3.0 * c.dx; // origin not at a corner
    expectSizeRenders(hf, 16, c.name);
  }
}

// Refused sizes: the message says what is wrong; nothing is allocated for absurd sizes (the
// heights vector stays empty, so an attempt to touch nx*ny heights would crash or throw).
TEST(StressSizes, RefusedSizesGiveClearErrors)
{
  struct Case
  {
    int nx, ny;
    const char* expect;
  };
  const Case cases[] = { { 1, 50, "at least 2 x 2" }, { 50, 1, "at least 2 x 2" }, { 0, 7, "at least 2 x 2" },
    { 0, 0, "at least 2 x 2" }, { -4, 5, "at least 2 x 2" }, { INT_MIN, 3, "at least 2 x 2" },
    { 65536, 65537, "at most 2^32 - 1" }, { INT_MAX, INT_MAX, "at most 2^32 - 1" },
    { INT_MAX, 2, "holds 0 heights" } /* 2^32 - 2 samples: indexable, but no heights given */ };
  for (const Case& c : cases)
  {
    gmm::Heightfield hf;
    hf.nx = c.nx;
    hf.ny = c.ny;
    gmm::Engine e;
    const std::string err = e.setHeightfield(hf, 64, 1);
    EXPECT_NE(err.find(c.expect), std::string::npos) << c.nx << "x" << c.ny << ": " << err;
    EXPECT_TRUE(e.empty());
    EXPECT_EQ(e.update(overview(sized(3, 3)), 1.0).triangles, 0u);
    EXPECT_EQ(e.lastError(), "no heightfield");
  }
  gmm::Heightfield hf = sized(5, 5);
  gmm::Engine e;
  EXPECT_NE(e.setHeightfield(hf, 3, 1).find("minimum of 4"), std::string::npos);
  EXPECT_NE(e.setHeightfield(hf, -7, 1).find("minimum of 4"), std::string::npos);
  hf.dx = 1e308; // finite spacing, but the extent 4e308 overflows
  EXPECT_NE(e.setHeightfield(hf, 16, 1).find("overflows"), std::string::npos);
  hf.dx = 5e-324; // denormal spacing is finite and non-zero: accepted
  EXPECT_EQ(e.setHeightfield(hf, 16, 1), "");
  EXPECT_EQ(e.updateForError(0.0).triangles, 32u);
}
